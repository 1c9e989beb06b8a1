// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): common::Time, seconds and nanoseconds as
// Gazebo keeps them (nsec in [0, 1e9), normalised after every operation).
#ifndef GAZEBO_COMMON_TIME_HH_
#define GAZEBO_COMMON_TIME_HH_

#include <cstdint>
#include <iostream>
#include <string>

#include "gazebo/util/system.hh"

namespace gazebo
{
namespace common
{
class GZ_COMMON_VISIBLE Time
{
public:
  Time();
  Time(int32_t _sec, int32_t _nsec);
  Time(double _time);  // NOLINT: implicit, as upstream's
  static const Time Zero;
  static const int32_t nsInSec;
  static const int32_t nsInMs;

  static const Time &GetWallTime();
  static const std::string &GetWallTimeAsISOString();
  void SetToWallTime();
  void Set(int32_t _sec, int32_t _nsec);
  void Set(double _seconds);
  double Double() const;
  float Float() const;
  std::string FormattedString() const;
  static Time Sleep(const common::Time &_time);
  static Time MSleep(unsigned int _ms);
  static Time NSleep(unsigned int _ns);
  static double SecToNano(double _sec) { return _sec * 1e9; }
  static double MilToNano(double _ms) { return _ms * 1e6; }
  static double MicToNano(double _ms) { return _ms * 1e3; }

  Time &operator=(const Time &_time) = default;
  Time(const Time &_time) = default;
  Time operator+(const Time &_time) const;
  const Time &operator+=(const Time &_time);
  Time operator-(const Time &_time) const;
  const Time &operator-=(const Time &_time);
  Time operator*(const Time &_time) const;
  const Time &operator*=(const Time &_time);
  Time operator/(const Time &_time) const;
  const Time &operator/=(const Time &_time);
  bool operator==(const Time &_time) const;
  bool operator==(double _time) const;
  bool operator!=(const Time &_time) const;
  bool operator!=(double _time) const;
  bool operator<(const Time &_time) const;
  bool operator<(double _time) const;
  bool operator<=(const Time &_time) const;
  bool operator<=(double _time) const;
  bool operator>(const Time &_time) const;
  bool operator>(double _time) const;
  bool operator>=(const Time &_time) const;
  bool operator>=(double _time) const;

  friend std::ostream &operator<<(std::ostream &_out, const Time &_time)
  {
    _out << _time.sec << " " << _time.nsec;
    return _out;
  }

  int32_t sec;
  int32_t nsec;

private:
  void Correct();
};
}  // namespace common
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): common::Exception and gzthrow.
#ifndef GAZEBO_COMMON_EXCEPTION_HH_
#define GAZEBO_COMMON_EXCEPTION_HH_

#include <sstream>
#include <stdexcept>
#include <string>

#include "gazebo/util/system.hh"

namespace gazebo
{
namespace common
{
class GZ_COMMON_VISIBLE Exception : public std::runtime_error
{
public:
  Exception(const char *_file, int64_t _line, std::string _msg)
    : std::runtime_error(_msg), file(_file), line(_line), msg(std::move(_msg)) {}
  std::string GetErrorFile() const { return this->file; }
  std::string GetErrorStr() const { return this->msg; }
  void Print() const;

private:
  std::string file;
  int64_t line;
  std::string msg;
};
}  // namespace common
}  // namespace gazebo

#define gzthrow(msg) \
  { std::ostringstream racebot_gzthrow_stream; racebot_gzthrow_stream << msg; \
    throw gazebo::common::Exception(__FILE__, __LINE__, racebot_gzthrow_stream.str()); }

#endif

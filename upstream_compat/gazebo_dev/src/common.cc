// racebot's Gazebo 11 plugin API: common (Time, Console, Exception) and the events' registry.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <mutex>
#include <thread>
#include <vector>

#include "gazebo/common/Console.hh"
#include "gazebo/common/Event.hh"
#include "gazebo/common/Events.hh"
#include "gazebo/common/Exception.hh"
#include "gazebo/common/Time.hh"

namespace gazebo
{
namespace common
{
const Time Time::Zero(0, 0);
const int32_t Time::nsInSec = 1000000000;
const int32_t Time::nsInMs = 1000000;

Time::Time() : sec(0), nsec(0) {}
Time::Time(int32_t _sec, int32_t _nsec) : sec(_sec), nsec(_nsec) { this->Correct(); }
Time::Time(double _time) { this->Set(_time); }

const Time &Time::GetWallTime()
{
  static thread_local Time wall;
  wall.SetToWallTime();
  return wall;
}

const std::string &Time::GetWallTimeAsISOString()
{
  static thread_local std::string text;
  std::time_t now = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%FT%T", std::localtime(&now));
  text = buffer;
  return text;
}

void Time::SetToWallTime()
{
  auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::system_clock::now().time_since_epoch()).count();
  this->sec = static_cast<int32_t>(ns / nsInSec);
  this->nsec = static_cast<int32_t>(ns % nsInSec);
}

void Time::Set(int32_t _sec, int32_t _nsec)
{
  this->sec = _sec;
  this->nsec = _nsec;
  this->Correct();
}

void Time::Set(double _seconds)
{
  this->sec = static_cast<int32_t>(std::floor(_seconds));
  this->nsec = static_cast<int32_t>(std::round((_seconds - this->sec) * 1e9));
  this->Correct();
}

double Time::Double() const { return this->sec + this->nsec * 1e-9; }
float Time::Float() const { return static_cast<float>(this->Double()); }

std::string Time::FormattedString() const
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%02d:%02d:%02d.%03d", this->sec / 3600, (this->sec / 60) % 60,
                this->sec % 60, this->nsec / nsInMs);
  return buffer;
}

Time Time::Sleep(const Time &_time)
{
  std::this_thread::sleep_for(std::chrono::seconds(_time.sec) + std::chrono::nanoseconds(_time.nsec));
  return Time::Zero;
}
Time Time::MSleep(unsigned int _ms) { return Sleep(Time(0, static_cast<int32_t>(_ms) * nsInMs)); }
Time Time::NSleep(unsigned int _ns) { return Sleep(Time(0, static_cast<int32_t>(_ns))); }

Time Time::operator+(const Time &_t) const { return Time(this->sec + _t.sec, this->nsec + _t.nsec); }
const Time &Time::operator+=(const Time &_t) { this->Set(this->sec + _t.sec, this->nsec + _t.nsec); return *this; }
Time Time::operator-(const Time &_t) const { return Time(this->sec - _t.sec, this->nsec - _t.nsec); }
const Time &Time::operator-=(const Time &_t) { this->Set(this->sec - _t.sec, this->nsec - _t.nsec); return *this; }
Time Time::operator*(const Time &_t) const { return Time(this->Double() * _t.Double()); }
const Time &Time::operator*=(const Time &_t) { this->Set(this->Double() * _t.Double()); return *this; }
Time Time::operator/(const Time &_t) const { return Time(this->Double() / _t.Double()); }
const Time &Time::operator/=(const Time &_t) { this->Set(this->Double() / _t.Double()); return *this; }
bool Time::operator==(const Time &_t) const { return this->sec == _t.sec && this->nsec == _t.nsec; }
bool Time::operator==(double _t) const { return *this == Time(_t); }
bool Time::operator!=(const Time &_t) const { return !(*this == _t); }
bool Time::operator!=(double _t) const { return !(*this == _t); }
bool Time::operator<(const Time &_t) const { return this->sec < _t.sec || (this->sec == _t.sec && this->nsec < _t.nsec); }
bool Time::operator<(double _t) const { return *this < Time(_t); }
bool Time::operator<=(const Time &_t) const { return !(_t < *this); }
bool Time::operator<=(double _t) const { return *this <= Time(_t); }
bool Time::operator>(const Time &_t) const { return _t < *this; }
bool Time::operator>(double _t) const { return *this > Time(_t); }
bool Time::operator>=(const Time &_t) const { return !(*this < _t); }
bool Time::operator>=(double _t) const { return *this >= Time(_t); }

void Time::Correct()
{
  // nsec into [0, 1e9), carrying into sec, as upstream's Correct
  this->sec += this->nsec / nsInSec;
  this->nsec %= nsInSec;
  if (this->nsec < 0)
  {
    this->nsec += nsInSec;
    this->sec -= 1;
  }
}

namespace
{
bool quiet = false;
std::ostream &Prefixed(std::ostream &_out, const char *_tag, const char *_file, int _line)
{
  std::string file(_file == nullptr ? "" : _file);
  const auto slash = file.rfind('/');
  if (slash != std::string::npos)
    file = file.substr(slash + 1);
  _out << "[" << _tag << "] [" << file << ":" << _line << "] ";
  return _out;
}
}  // namespace

std::ostream &Console::Msg()
{
  std::cout << "[Msg] ";
  return std::cout;
}
std::ostream &Console::Warn(const char *_file, int _line) { return Prefixed(std::cerr, "Wrn", _file, _line); }
std::ostream &Console::Err(const char *_file, int _line) { return Prefixed(std::cerr, "Err", _file, _line); }
std::ostream &Console::Dbg(const char *_file, int _line)
{
  static std::ostringstream discard;  // Gazebo prints gzdbg only with --verbose and a debug build
  discard.str("");
  (void)_file;
  (void)_line;
  return discard;
}
std::ostream &Console::Log()
{
  static std::ostringstream discard;  // Gazebo's log file; racebot keeps none
  discard.str("");
  return discard;
}
void Console::SetQuiet(bool _quiet) { quiet = _quiet; }
bool Console::GetQuiet() { return quiet; }

void Exception::Print() const { gzerr << "EXCEPTION: " << this->msg << "\n"; }
}  // namespace common

namespace event
{
namespace detail
{
namespace
{
thread_local int currentOwner = 0;
std::mutex failuresMutex;
std::vector<std::pair<int, std::string>> failures;
}  // namespace

int CurrentOwner() { return currentOwner; }
void SetCurrentOwner(int _owner) { currentOwner = _owner; }

void ReportFailure(int _owner, const std::string &_what)
{
  std::lock_guard<std::mutex> lock(failuresMutex);
  failures.emplace_back(_owner, _what);
}

std::vector<std::pair<int, std::string>> TakeFailures()
{
  std::lock_guard<std::mutex> lock(failuresMutex);
  std::vector<std::pair<int, std::string>> taken;
  taken.swap(failures);
  return taken;
}
}  // namespace detail

namespace
{
std::mutex &EventsMutex()
{
  static std::mutex mutex;
  return mutex;
}
std::vector<Event *> &AllEvents()
{
  static std::vector<Event *> events;  // never destroyed before the events themselves (function-local static)
  return events;
}
}  // namespace

void RegisterEvent(Event *_event)
{
  std::lock_guard<std::mutex> lock(EventsMutex());
  AllEvents().push_back(_event);
}

void UnregisterEvent(Event *_event)
{
  std::lock_guard<std::mutex> lock(EventsMutex());
  auto &events = AllEvents();
  events.erase(std::remove(events.begin(), events.end(), _event), events.end());
}

void DisconnectOwnerEverywhere(int _owner)
{
  std::vector<Event *> events;
  {
    std::lock_guard<std::mutex> lock(EventsMutex());
    events = AllEvents();
  }
  for (Event *event : events)
    event->DisconnectOwner(_owner);
}

EventT<void (bool)> Events::pause;
EventT<void ()> Events::step;
EventT<void ()> Events::stop;
EventT<void ()> Events::sigInt;
EventT<void (std::string)> Events::worldCreated;
EventT<void (std::string)> Events::entityCreated;
EventT<void (std::string, std::string)> Events::setSelectedEntity;
EventT<void (std::string)> Events::addEntity;
EventT<void (std::string)> Events::deleteEntity;
EventT<void (const common::UpdateInfo &)> Events::worldUpdateBegin;
EventT<void (const common::UpdateInfo &)> Events::beforePhysicsUpdate;
EventT<void ()> Events::worldUpdateEnd;
EventT<void ()> Events::worldReset;
EventT<void ()> Events::timeReset;
EventT<void ()> Events::preRender;
EventT<void ()> Events::render;
EventT<void ()> Events::postRender;
EventT<void (std::string)> Events::diagTimerStart;
EventT<void (std::string)> Events::diagTimerStop;
EventT<void (std::string)> Events::removeSensor;
EventT<void (sdf::ElementPtr, const std::string &, const std::string &, const uint32_t)> Events::createSensor;
}  // namespace event
}  // namespace gazebo

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): gzmsg, gzwarn, gzerr, gzdbg and gzlog, written as
// Gazebo writes them ("[Msg] ...", "[Wrn] [file:line] ...", "[Err] [file:line] ..."), to the world server's
// stdout and stderr (roslaunch's screen or log).
#ifndef GAZEBO_COMMON_CONSOLE_HH_
#define GAZEBO_COMMON_CONSOLE_HH_

#include <iostream>
#include <sstream>
#include <string>

#include "gazebo/util/system.hh"

namespace gazebo
{
namespace common
{
class GZ_COMMON_VISIBLE Console
{
public:
  static std::ostream &Msg();
  static std::ostream &Warn(const char *_file, int _line);
  static std::ostream &Err(const char *_file, int _line);
  static std::ostream &Dbg(const char *_file, int _line);
  static std::ostream &Log();
  static void SetQuiet(bool _quiet);
  static bool GetQuiet();
};
}  // namespace common
}  // namespace gazebo

#define gzmsg (gazebo::common::Console::Msg())
#define gzdbg (gazebo::common::Console::Dbg(__FILE__, __LINE__))
#define gzwarn (gazebo::common::Console::Warn(__FILE__, __LINE__))
#define gzerr (gazebo::common::Console::Err(__FILE__, __LINE__))
#define gzlog (gazebo::common::Console::Log())

#endif

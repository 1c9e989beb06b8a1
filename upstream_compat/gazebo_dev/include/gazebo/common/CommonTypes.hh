// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the common forward declarations, as Gazebo's
// CommonTypes.hh gives every header that includes Plugin.hh or the physics types (event::ConnectionPtr for a
// plugin's member `event::ConnectionPtr updateConnection;`), and Gazebo's version macros with them.
#ifndef GAZEBO_COMMON_COMMONTYPES_HH_
#define GAZEBO_COMMON_COMMONTYPES_HH_

#include <memory>
#include <vector>

#include "gazebo/gazebo_config.h"

namespace gazebo
{
namespace common
{
class Time;
}  // namespace common

namespace event
{
class Connection;
typedef std::shared_ptr<Connection> ConnectionPtr;
typedef std::vector<ConnectionPtr> Connection_V;
}  // namespace event
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): what a world update event carries.
#ifndef GAZEBO_COMMON_UPDATEINFO_HH_
#define GAZEBO_COMMON_UPDATEINFO_HH_

#include <string>

#include "gazebo/common/Time.hh"

namespace gazebo
{
namespace common
{
class UpdateInfo
{
public:
  std::string worldName;
  common::Time simTime;   // the sim time this update steps to (Gazebo adds the step before World::Update)
  common::Time realTime;  // wall time since the world server started
};
}  // namespace common
}  // namespace gazebo

#endif

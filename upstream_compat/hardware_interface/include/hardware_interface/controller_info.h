// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
#ifndef HARDWARE_INTERFACE_CONTROLLER_INFO_H
#define HARDWARE_INTERFACE_CONTROLLER_INFO_H

#include <string>
#include <vector>

#include <hardware_interface/interface_resources.h>

namespace hardware_interface
{

// A controller as RobotHW's switch and conflict checks see it.
struct ControllerInfo
{
  std::string name;
  std::string type;
  std::vector<InterfaceResources> claimed_resources;
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_CONTROLLER_INFO_H

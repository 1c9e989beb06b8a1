// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
#ifndef HARDWARE_INTERFACE_INTERFACE_RESOURCES_H
#define HARDWARE_INTERFACE_INTERFACE_RESOURCES_H

#include <set>
#include <string>

namespace hardware_interface
{

// The resources a controller claims from one hardware interface (list_controllers' claimed_resources).
struct InterfaceResources
{
  InterfaceResources() = default;
  InterfaceResources(const std::string& hw_iface, const std::set<std::string>& res)
    : hardware_interface(hw_iface), resources(res)
  {
  }

  std::string hardware_interface;
  std::set<std::string> resources;
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_INTERFACE_RESOURCES_H

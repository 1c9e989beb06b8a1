// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
// A hardware interface made of named handles; with ClaimResources, taking a handle claims its resource (command
// interfaces), with DontClaimResources it does not (state interfaces).
#ifndef HARDWARE_INTERFACE_INTERNAL_HARDWARE_RESOURCE_MANAGER_H
#define HARDWARE_INTERFACE_INTERNAL_HARDWARE_RESOURCE_MANAGER_H

#include <stdexcept>
#include <string>

#include <hardware_interface/hardware_interface.h>
#include <hardware_interface/internal/resource_manager.h>

namespace hardware_interface
{

struct ClaimResources
{
  static void claim(HardwareInterface* hw, const std::string& name) { hw->claim(name); }
};

struct DontClaimResources
{
  static void claim(HardwareInterface*, const std::string&) {}
};

template <class ResourceHandle, class ClaimPolicy = DontClaimResources>
class HardwareResourceManager : public HardwareInterface, public ResourceManager<ResourceHandle>
{
public:
  typedef ResourceHandle ResourceHandleType;

  // HardwareInterfaceException when there is no such handle.
  ResourceHandle getHandle(const std::string& name)
  {
    try
    {
      ResourceHandle handle = ResourceManager<ResourceHandle>::getHandle(name);
      ClaimPolicy::claim(this, name);
      return handle;
    }
    catch (const std::logic_error& error)
    {
      throw HardwareInterfaceException(error.what());
    }
  }
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_INTERNAL_HARDWARE_RESOURCE_MANAGER_H

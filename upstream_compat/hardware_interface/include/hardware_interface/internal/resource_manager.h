// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
// Handles by name: what a hardware interface holds and a controller asks for.
#ifndef HARDWARE_INTERFACE_INTERNAL_RESOURCE_MANAGER_H
#define HARDWARE_INTERFACE_INTERNAL_RESOURCE_MANAGER_H

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <ros/console.h>

#include <hardware_interface/internal/demangle_symbol.h>

namespace hardware_interface
{

class ResourceManagerBase
{
public:
  virtual ~ResourceManagerBase() = default;
};

template <class ResourceHandle>
class ResourceManager : public ResourceManagerBase
{
public:
  typedef ResourceManager<ResourceHandle> ResourceManagerType;

  std::vector<std::string> getNames() const
  {
    std::vector<std::string> names;
    names.reserve(resource_map_.size());
    for (const auto& entry : resource_map_)
      names.push_back(entry.first);
    return names;
  }

  // A second handle of the same name replaces the first, with a warning.
  void registerHandle(const ResourceHandle& handle)
  {
    auto found = resource_map_.find(handle.getName());
    if (found != resource_map_.end())
    {
      ROS_WARN_STREAM("Replacing previously registered handle '" << handle.getName() << "' in '"
                      << internal::demangledTypeName(*this) << "'.");
      found->second = handle;
      return;
    }
    resource_map_.emplace(handle.getName(), handle);
  }

  // std::logic_error naming the resource and the manager when there is no such handle.
  ResourceHandle getHandle(const std::string& name)
  {
    auto found = resource_map_.find(name);
    if (found == resource_map_.end())
      throw std::logic_error("Could not find resource '" + name + "' in '" + internal::demangledTypeName(*this) +
                             "'.");
    return found->second;
  }

  // Every handle of `managers` registered in `result` (RobotHW::get<T> of interfaces from several RobotHWs).
  static void concatManagers(std::vector<ResourceManagerType*>& managers, ResourceManagerType* result)
  {
    for (ResourceManagerType* manager : managers)
      for (const std::string& name : manager->getNames())
        result->registerHandle(manager->getHandle(name));
  }

protected:
  typedef std::map<std::string, ResourceHandle> ResourceMap;
  ResourceMap resource_map_;
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_INTERNAL_RESOURCE_MANAGER_H

// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
// Hardware interfaces by type: RobotHW::registerInterface(&iface) and get<T>(), across nested interface managers
// (a combined RobotHW), keyed by the demangled type name as upstream's are.
#ifndef HARDWARE_INTERFACE_INTERNAL_INTERFACE_MANAGER_H
#define HARDWARE_INTERFACE_INTERNAL_INTERFACE_MANAGER_H

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ros/console.h>

#include <hardware_interface/internal/demangle_symbol.h>
#include <hardware_interface/internal/resource_manager.h>

namespace hardware_interface
{
namespace internal
{

// What InterfaceManager does with a T that is a ResourceManager (has T::ResourceManagerType) and with one that is
// not, chosen by overload (C++11: packages build with -std=c++11 too): the first overload of each pair is viable
// only for a ResourceManager, the variadic one always, and ranks last.
template <class T>
struct CheckIsResourceManager
{
  template <class C>
  static void getResources(std::vector<std::string>& resources, C* iface, typename C::ResourceManagerType*)
  {
    resources = iface->getNames();
  }
  template <class C>
  static void getResources(std::vector<std::string>&, C*, ...)
  {
  }
  static void callGetResources(std::vector<std::string>& resources, T* iface)
  {
    getResources<T>(resources, iface, nullptr);
  }

  template <class C>
  static C* combine(std::vector<std::unique_ptr<ResourceManagerBase>>& guards, std::vector<C*>& managers,
                    typename C::ResourceManagerType*)
  {
    C* combined = new C;
    guards.emplace_back(combined);
    std::vector<typename C::ResourceManagerType*> parts(managers.begin(), managers.end());
    C::concatManagers(parts, combined);
    return combined;
  }
  template <class C>
  static C* combine(std::vector<std::unique_ptr<ResourceManagerBase>>&, std::vector<C*>&, ...)
  {
    ROS_ERROR("You cannot register multiple interfaces of the same type which are not of type ResourceManager. "
              "There is no established protocol for combining them.");
    return nullptr;
  }
  // A new T holding every handle of `managers`, owned by `guards`; nullptr (with an error) when T cannot combine.
  static T* newCombinedInterface(std::vector<std::unique_ptr<ResourceManagerBase>>& guards,
                                 std::vector<T*>& managers)
  {
    return combine<T>(guards, managers, nullptr);
  }
};

}  // namespace internal

class InterfaceManager
{
public:
  virtual ~InterfaceManager() = default;

  template <class T>
  void registerInterface(T* iface)
  {
    const std::string name = internal::demangledTypeName<T>();
    if (interfaces_.count(name))
      ROS_WARN_STREAM("Replacing previously registered interface '" << name << "'.");
    interfaces_[name] = iface;
    internal::CheckIsResourceManager<T>::callGetResources(resources_[name], iface);
  }

  void registerInterfaceManager(InterfaceManager* iface_man) { interface_managers_.push_back(iface_man); }

  // The interface of type T: this manager's, a nested manager's, or all of theirs combined; nullptr if none has one.
  template <class T>
  T* get()
  {
    const std::string name = internal::demangledTypeName<T>();
    std::vector<T*> found;
    auto own = interfaces_.find(name);
    if (own != interfaces_.end())
      found.push_back(static_cast<T*>(own->second));
    for (InterfaceManager* nested : interface_managers_)
      if (T* iface = nested->get<T>())
        found.push_back(iface);
    if (found.empty())
      return nullptr;
    if (found.size() == 1)
      return found.front();
    auto combined = interfaces_combo_.find(name);
    if (combined != interfaces_combo_.end() && num_ifaces_registered_[name] == found.size())
      return static_cast<T*>(combined->second);
    T* made = internal::CheckIsResourceManager<T>::newCombinedInterface(interface_destruction_list_, found);
    if (made)
    {
      interfaces_combo_[name] = made;
      num_ifaces_registered_[name] = found.size();
    }
    return made;
  }

  std::vector<std::string> getNames() const
  {
    std::vector<std::string> names;
    for (const auto& entry : interfaces_)
      names.push_back(entry.first);
    for (const InterfaceManager* nested : interface_managers_)
      for (const std::string& name : nested->getNames())
        if (std::find(names.begin(), names.end(), name) == names.end())
          names.push_back(name);
    return names;
  }

  std::vector<std::string> getInterfaceResources(std::string iface_type) const
  {
    std::vector<std::string> resources;
    auto own = resources_.find(iface_type);
    if (own != resources_.end())
      resources = own->second;
    for (const InterfaceManager* nested : interface_managers_)
    {
      std::vector<std::string> more = nested->getInterfaceResources(iface_type);
      resources.insert(resources.end(), more.begin(), more.end());
    }
    return resources;
  }

protected:
  typedef std::map<std::string, void*> InterfaceMap;
  typedef std::vector<InterfaceManager*> InterfaceManagerVector;
  typedef std::map<std::string, size_t> SizeMap;
  typedef std::map<std::string, std::vector<std::string>> ResourceMap;

  InterfaceMap interfaces_;
  InterfaceMap interfaces_combo_;
  InterfaceManagerVector interface_managers_;
  SizeMap num_ifaces_registered_;
  std::vector<std::unique_ptr<ResourceManagerBase>> interface_destruction_list_;
  ResourceMap resources_;
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_INTERNAL_INTERFACE_MANAGER_H

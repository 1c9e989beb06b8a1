// racebot's controller_interface (upstream_compat/controller_interface): ros_control 0.20's API, written for
// racebot. What MultiInterfaceController does to each of its interface types, one fold expression each.
#ifndef CONTROLLER_INTERFACE_INTERNAL_ROBOTHW_INTERFACES_H
#define CONTROLLER_INTERFACE_INTERNAL_ROBOTHW_INTERFACES_H

#include <iterator>
#include <sstream>
#include <string>
#include <type_traits>

#include <controller_interface/controller_base.h>
#include <hardware_interface/internal/demangle_symbol.h>
#include <hardware_interface/robot_hw.h>

namespace controller_interface
{
namespace internal
{

// The elements of `val`, each between prefix and suffix, separated by delimiter.
template <class T>
inline std::string enumerateElements(const T& val, const std::string& delimiter, const std::string& prefix,
                                     const std::string& suffix)
{
  std::ostringstream out;
  bool first = true;
  for (const auto& element : val)
  {
    out << (first ? "" : delimiter) << prefix << element << suffix;
    first = false;
  }
  return out.str();
}

template <typename... T>
inline bool hasInterfaces(hardware_interface::RobotHW* robot_hw)
{
  auto has = [robot_hw](auto* tag, const std::string& name) {
    using I = std::remove_pointer_t<decltype(tag)>;
    if (robot_hw->get<I>())
      return true;
    ROS_ERROR_STREAM("This controller requires a hardware interface of type '"
                     << name << "', but is not exposed by the robot. Available interfaces in robot:\n"
                     << enumerateElements(robot_hw->getNames(), "\n", "- '", "'"));
    return false;
  };
  return (has(static_cast<T*>(nullptr), hardware_interface::internal::demangledTypeName<T>()) && ...);
}

template <typename... T>
inline void clearClaims(hardware_interface::RobotHW* robot_hw)
{
  auto clear = [](auto* hw) {
    if (hw)
      hw->clearClaims();
  };
  (clear(robot_hw->get<T>()), ...);
}

template <typename... T>
inline void extractInterfaceResources(hardware_interface::RobotHW* robot_hw_in,
                                      hardware_interface::RobotHW* robot_hw_out)
{
  auto extract = [robot_hw_out](auto* hw) {
    if (hw)
      robot_hw_out->registerInterface(hw);
  };
  (extract(robot_hw_in->get<T>()), ...);
}

template <typename... T>
inline void populateClaimedResources(hardware_interface::RobotHW* robot_hw,
                                     ControllerBase::ClaimedResources& claimed_resources)
{
  auto populate = [&claimed_resources](auto* hw, const std::string& name) {
    if (hw)
      claimed_resources.emplace_back(name, hw->getClaims());
  };
  (populate(robot_hw->get<T>(), hardware_interface::internal::demangledTypeName<T>()), ...);
}

}  // namespace internal
}  // namespace controller_interface

#endif  // CONTROLLER_INTERFACE_INTERNAL_ROBOTHW_INTERFACES_H

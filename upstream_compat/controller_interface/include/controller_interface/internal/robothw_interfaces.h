// racebot's controller_interface (upstream_compat/controller_interface): ros_control 0.20's API, written for
// racebot. What MultiInterfaceController does to each of its interface types.
#ifndef CONTROLLER_INTERFACE_INTERNAL_ROBOTHW_INTERFACES_H
#define CONTROLLER_INTERFACE_INTERNAL_ROBOTHW_INTERFACES_H

#include <iterator>
#include <sstream>
#include <string>

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

// Each of these takes the interface types T1, T2, ... one at a time (C++11: packages build with -std=c++11 too).
template <typename T>
inline bool hasInterfaces(hardware_interface::RobotHW* robot_hw)
{
  if (robot_hw->get<T>())
    return true;
  ROS_ERROR_STREAM("This controller requires a hardware interface of type '"
                   << hardware_interface::internal::demangledTypeName<T>()
                   << "', but is not exposed by the robot. Available interfaces in robot:\n"
                   << enumerateElements(robot_hw->getNames(), "\n", "- '", "'"));
  return false;
}
template <typename T1, typename T2, typename... More>
inline bool hasInterfaces(hardware_interface::RobotHW* robot_hw)
{
  return hasInterfaces<T1>(robot_hw) && hasInterfaces<T2, More...>(robot_hw);
}

template <typename T>
inline void clearClaims(hardware_interface::RobotHW* robot_hw)
{
  if (T* hw = robot_hw->get<T>())
    hw->clearClaims();
}
template <typename T1, typename T2, typename... More>
inline void clearClaims(hardware_interface::RobotHW* robot_hw)
{
  clearClaims<T1>(robot_hw);
  clearClaims<T2, More...>(robot_hw);
}

template <typename T>
inline void extractInterfaceResources(hardware_interface::RobotHW* robot_hw_in,
                                      hardware_interface::RobotHW* robot_hw_out)
{
  if (T* hw = robot_hw_in->get<T>())
    robot_hw_out->registerInterface(hw);
}
template <typename T1, typename T2, typename... More>
inline void extractInterfaceResources(hardware_interface::RobotHW* robot_hw_in,
                                      hardware_interface::RobotHW* robot_hw_out)
{
  extractInterfaceResources<T1>(robot_hw_in, robot_hw_out);
  extractInterfaceResources<T2, More...>(robot_hw_in, robot_hw_out);
}

template <typename T>
inline void populateClaimedResources(hardware_interface::RobotHW* robot_hw,
                                     ControllerBase::ClaimedResources& claimed_resources)
{
  if (T* hw = robot_hw->get<T>())
    claimed_resources.push_back(
        hardware_interface::InterfaceResources(hardware_interface::internal::demangledTypeName<T>(), hw->getClaims()));
}
template <typename T1, typename T2, typename... More>
inline void populateClaimedResources(hardware_interface::RobotHW* robot_hw,
                                     ControllerBase::ClaimedResources& claimed_resources)
{
  populateClaimedResources<T1>(robot_hw, claimed_resources);
  populateClaimedResources<T2, More...>(robot_hw, claimed_resources);
}

}  // namespace internal
}  // namespace controller_interface

#endif  // CONTROLLER_INTERFACE_INTERNAL_ROBOTHW_INTERFACES_H

// racebot's controller_interface (upstream_compat/controller_interface): ros_control 0.20's API, written for
// racebot. A controller of several hardware interface types: init gets a RobotHW holding only those.
#ifndef CONTROLLER_INTERFACE_MULTI_INTERFACE_CONTROLLER_H
#define CONTROLLER_INTERFACE_MULTI_INTERFACE_CONTROLLER_H

#include <ros/ros.h>

#include <controller_interface/controller_base.h>
#include <controller_interface/internal/robothw_interfaces.h>
#include <hardware_interface/hardware_interface.h>
#include <hardware_interface/internal/demangle_symbol.h>
#include <hardware_interface/robot_hw.h>

namespace controller_interface
{

template <typename... T>
class MultiInterfaceController : public virtual ControllerBase
{
public:
  // allow_optional_interfaces: init runs even when the robot lacks some of T (its get<> then gives nullptr).
  MultiInterfaceController(bool allow_optional_interfaces = false)
    : allow_optional_interfaces_(allow_optional_interfaces)
  {
  }

  virtual bool init(hardware_interface::RobotHW* /*robot_hw*/, ros::NodeHandle& /*controller_nh*/) { return true; }
  virtual bool init(hardware_interface::RobotHW* /*robot_hw*/, ros::NodeHandle& /*root_nh*/,
                    ros::NodeHandle& /*controller_nh*/)
  {
    return true;
  }

protected:
  bool initRequest(hardware_interface::RobotHW* robot_hw, ros::NodeHandle& root_nh, ros::NodeHandle& controller_nh,
                   ClaimedResources& claimed_resources) override
  {
    if (state_ != ControllerState::CONSTRUCTED)
    {
      ROS_ERROR("Cannot initialize this controller because it failed to be constructed");
      return false;
    }
    if (!allow_optional_interfaces_ && !hasRequiredInterfaces(robot_hw))
      return false;
    hardware_interface::RobotHW* own = &robot_hw_ctrl_;
    extractInterfaceResources(robot_hw, own);
    clearClaims(own);
    if (!init(own, controller_nh) || !init(own, root_nh, controller_nh))
    {
      ROS_ERROR("Failed to initialize the controller");
      return false;
    }
    claimed_resources.clear();
    populateClaimedResources(own, claimed_resources);
    clearClaims(own);
    state_ = ControllerState::INITIALIZED;
    return true;
  }

  static bool hasRequiredInterfaces(hardware_interface::RobotHW* robot_hw)
  {
    return internal::hasInterfaces<T...>(robot_hw);
  }
  static void clearClaims(hardware_interface::RobotHW* robot_hw) { internal::clearClaims<T...>(robot_hw); }
  static void extractInterfaceResources(hardware_interface::RobotHW* robot_hw_in,
                                        hardware_interface::RobotHW* robot_hw_out)
  {
    internal::extractInterfaceResources<T...>(robot_hw_in, robot_hw_out);
  }
  static void populateClaimedResources(hardware_interface::RobotHW* robot_hw, ClaimedResources& claimed_resources)
  {
    internal::populateClaimedResources<T...>(robot_hw, claimed_resources);
  }

  hardware_interface::RobotHW robot_hw_ctrl_;  // only the interfaces of T..., what init gets
  bool allow_optional_interfaces_;
};

}  // namespace controller_interface

#endif  // CONTROLLER_INTERFACE_MULTI_INTERFACE_CONTROLLER_H

// racebot's controller_interface (upstream_compat/controller_interface): ros_control 0.20's API, written for
// racebot. A controller of one hardware interface type T (VelocityJointInterface, ...).
#ifndef CONTROLLER_INTERFACE_CONTROLLER_H
#define CONTROLLER_INTERFACE_CONTROLLER_H

#include <string>

#include <ros/ros.h>

#include <controller_interface/controller_base.h>
#include <hardware_interface/hardware_interface.h>
#include <hardware_interface/internal/demangle_symbol.h>
#include <hardware_interface/robot_hw.h>

namespace controller_interface
{

template <class T>
class Controller : public virtual ControllerBase
{
public:
  // A controller overrides one of these; both are called, the two-handle one second.
  virtual bool init(T* /*hw*/, ros::NodeHandle& /*controller_nh*/) { return true; }
  virtual bool init(T* /*hw*/, ros::NodeHandle& /*root_nh*/, ros::NodeHandle& /*controller_nh*/) { return true; }

protected:
  bool initRequest(hardware_interface::RobotHW* robot_hw, ros::NodeHandle& root_nh, ros::NodeHandle& controller_nh,
                   ClaimedResources& claimed_resources) override
  {
    if (state_ != ControllerState::CONSTRUCTED)
    {
      ROS_ERROR("Cannot initialize this controller because it failed to be constructed");
      return false;
    }
    T* hw = robot_hw->get<T>();
    if (!hw)
    {
      ROS_ERROR("This controller requires a hardware interface of type '%s'. Make sure this is registered in the "
                "hardware_interface::RobotHW class.",
                getHardwareInterfaceType().c_str());
      return false;
    }
    hw->clearClaims();  // what init takes from hw is what this controller claims
    if (!init(hw, controller_nh) || !init(hw, root_nh, controller_nh))
    {
      ROS_ERROR("Failed to initialize the controller");
      return false;
    }
    claimed_resources.assign(1, hardware_interface::InterfaceResources(getHardwareInterfaceType(), hw->getClaims()));
    hw->clearClaims();
    state_ = ControllerState::INITIALIZED;
    return true;
  }

  std::string getHardwareInterfaceType() const { return hardware_interface::internal::demangledTypeName<T>(); }
};

}  // namespace controller_interface

#endif  // CONTROLLER_INTERFACE_CONTROLLER_H

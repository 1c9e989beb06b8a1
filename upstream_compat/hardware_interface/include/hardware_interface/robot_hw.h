// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
// A robot's hardware: its interfaces (InterfaceManager), read/write, and the checks a controller switch asks of it.
#ifndef HARDWARE_INTERFACE_ROBOT_HW_H
#define HARDWARE_INTERFACE_ROBOT_HW_H

#include <list>
#include <map>
#include <memory>
#include <string>

#include <ros/console.h>
#include <ros/node_handle.h>

#include <hardware_interface/controller_info.h>
#include <hardware_interface/hardware_interface.h>
#include <hardware_interface/internal/interface_manager.h>

namespace hardware_interface
{

class RobotHW : public InterfaceManager
{
public:
  virtual ~RobotHW() = default;

  virtual bool init(ros::NodeHandle& /*root_nh*/, ros::NodeHandle& /*robot_hw_nh*/) { return true; }

  // True (with a warning naming them) when two controllers of `info` claim the same resource.
  virtual bool checkForConflict(const std::list<ControllerInfo>& info) const
  {
    std::map<std::string, std::list<std::string>> claimants;
    for (const ControllerInfo& controller : info)
      for (const InterfaceResources& claimed : controller.claimed_resources)
        for (const std::string& resource : claimed.resources)
          claimants[resource].push_back(controller.name);
    bool conflict = false;
    for (const auto& entry : claimants)
    {
      if (entry.second.size() < 2)
        continue;
      std::string names;
      for (const std::string& name : entry.second)
        names += name + ", ";
      ROS_WARN("Resource conflict on [%s].  Controllers = [%s]", entry.first.c_str(), names.c_str());
      conflict = true;
    }
    return conflict;
  }

  virtual bool prepareSwitch(const std::list<ControllerInfo>& /*start_list*/,
                             const std::list<ControllerInfo>& /*stop_list*/)
  {
    return true;
  }
  virtual void doSwitch(const std::list<ControllerInfo>& /*start_list*/,
                        const std::list<ControllerInfo>& /*stop_list*/)
  {
  }

  enum class SwitchState
  {
    DONE,
    ONGOING,
    ERROR
  };
  virtual SwitchState switchResult() const { return SwitchState::DONE; }
  virtual SwitchState switchResult(const ControllerInfo& /*controller*/) const { return SwitchState::DONE; }

  virtual void read(const ros::Time& /*time*/, const ros::Duration& /*period*/) {}
  virtual void write(const ros::Time& /*time*/, const ros::Duration& /*period*/) {}
};

typedef std::shared_ptr<RobotHW> RobotHWSharedPtr;

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_ROBOT_HW_H

// racebot's controller_interface (upstream_compat/controller_interface): ros_control 0.20's API, written for
// racebot. What a controller manager drives: a controller's state and its start, update, stop, wait and abort.
#ifndef CONTROLLER_INTERFACE_CONTROLLER_BASE_H
#define CONTROLLER_INTERFACE_CONTROLLER_BASE_H

#include <memory>
#include <vector>

#include <ros/console.h>
#include <ros/node_handle.h>

#include <hardware_interface/interface_resources.h>
#include <hardware_interface/robot_hw.h>

namespace controller_interface
{

class ControllerBase
{
public:
  ControllerBase() = default;
  virtual ~ControllerBase() = default;
  ControllerBase(const ControllerBase&) = delete;
  ControllerBase& operator=(const ControllerBase&) = delete;
  ControllerBase(ControllerBase&&) = delete;
  ControllerBase& operator=(ControllerBase&&) = delete;

  // What a controller overrides (update at least), called from the control loop.
  virtual void starting(const ros::Time& /*time*/) {}
  virtual void update(const ros::Time& time, const ros::Duration& period) = 0;
  virtual void stopping(const ros::Time& /*time*/) {}
  virtual void waiting(const ros::Time& /*time*/) {}
  virtual void aborting(const ros::Time& /*time*/) {}

  bool isInitialized() const { return state_ == ControllerState::INITIALIZED; }
  bool isRunning() const { return state_ == ControllerState::RUNNING; }
  bool isStopped() const { return state_ == ControllerState::STOPPED; }
  bool isWaiting() const { return state_ == ControllerState::WAITING; }
  bool isAborted() const { return state_ == ControllerState::ABORTED; }

  // What the controller manager calls.
  void updateRequest(const ros::Time& time, const ros::Duration& period)
  {
    if (state_ == ControllerState::RUNNING)
      update(time, period);
  }
  bool startRequest(const ros::Time& time) { return change(time, &ControllerBase::starting, ControllerState::RUNNING, "start"); }
  bool stopRequest(const ros::Time& time) { return change(time, &ControllerBase::stopping, ControllerState::STOPPED, "stop"); }
  bool waitRequest(const ros::Time& time) { return change(time, &ControllerBase::waiting, ControllerState::WAITING, "wait"); }
  bool abortRequest(const ros::Time& time) { return change(time, &ControllerBase::aborting, ControllerState::ABORTED, "abort"); }

  typedef std::vector<hardware_interface::InterfaceResources> ClaimedResources;

  // Takes the controller's interfaces from robot_hw, calls its init, and lists the resources it claimed.
  virtual bool initRequest(hardware_interface::RobotHW* robot_hw, ros::NodeHandle& root_nh,
                           ros::NodeHandle& controller_nh, ClaimedResources& claimed_resources) = 0;

  enum class ControllerState
  {
    CONSTRUCTED,
    INITIALIZED,
    RUNNING,
    STOPPED,
    WAITING,
    ABORTED
  };
  ControllerState state_ = ControllerState::CONSTRUCTED;

private:
  bool change(const ros::Time& time, void (ControllerBase::*hook)(const ros::Time&), ControllerState next,
              const char* what)
  {
    if (state_ == ControllerState::CONSTRUCTED)
    {
      ROS_FATAL("Failed to %s controller. It is not initialized.", what);
      return false;
    }
    (this->*hook)(time);
    state_ = next;
    return true;
  }
};

typedef std::shared_ptr<ControllerBase> ControllerBaseSharedPtr;

}  // namespace controller_interface

#endif  // CONTROLLER_INTERFACE_CONTROLLER_BASE_H

// racebot's gazebo_ros_control (upstream_compat/gazebo_ros_control): gazebo_ros_control 2.9's RobotHWSim, written
// for racebot. A robot's simulated hardware as a pluginlib class (<robotSimType>): initSim gets the model (racebot's
// Gazebo 11 plugin API, upstream_compat/gazebo_dev), its URDF and transmissions; readSim and writeSim run around the
// controllers at every control period, as gazebo_ros_control's plugin runs them.
#ifndef GAZEBO_ROS_CONTROL_ROBOT_HW_SIM_H
#define GAZEBO_ROS_CONTROL_ROBOT_HW_SIM_H

#include <string>
#include <vector>

#include <gazebo/physics/physics.hh>
#include <hardware_interface/robot_hw.h>
#include <ros/ros.h>
#include <transmission_interface/transmission_info.h>
#include <urdf/model.h>

namespace gazebo_ros_control
{

struct JointData
{
  std::string name_;
  std::string hardware_interface_;

  JointData(const std::string& name, const std::string& hardware_interface)
    : name_(name), hardware_interface_(hardware_interface)
  {
  }
};

class RobotHWSim : public hardware_interface::RobotHW
{
public:
  virtual ~RobotHWSim() {}

  virtual bool initSim(const std::string& robot_namespace, ros::NodeHandle model_nh,
                       gazebo::physics::ModelPtr parent_model, const urdf::Model* const urdf_model,
                       std::vector<transmission_interface::TransmissionInfo> transmissions) = 0;

  virtual void readSim(ros::Time time, ros::Duration period) = 0;
  virtual void writeSim(ros::Time time, ros::Duration period) = 0;

  // The plugin's <eStopTopic>: true while the emergency stop is active.
  virtual void eStopActive(const bool /*active*/) {}
};

}  // namespace gazebo_ros_control

#endif  // GAZEBO_ROS_CONTROL_ROBOT_HW_SIM_H

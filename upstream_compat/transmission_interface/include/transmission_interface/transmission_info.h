// racebot's transmission_interface (upstream_compat/transmission_interface): ros_control 0.20's TransmissionInfo,
// written for racebot. A URDF <transmission> as gazebo_ros_control hands it to a RobotHWSim's initSim.
#ifndef TRANSMISSION_INTERFACE_TRANSMISSION_INFO_H
#define TRANSMISSION_INTERFACE_TRANSMISSION_INFO_H

#include <string>
#include <vector>

#include <tinyxml.h>  // upstream's header brings it; RobotHWSims parse xml_element_ with it

namespace transmission_interface
{

struct JointInfo
{
  std::string name_;
  std::vector<std::string> hardware_interfaces_;
  std::string role_;
  std::string xml_element_;  // the <joint> element, as text
};

struct ActuatorInfo
{
  std::string name_;
  std::vector<std::string> hardware_interfaces_;
  std::string xml_element_;  // the <actuator> element, as text
};

struct TransmissionInfo
{
  std::string name_;
  std::string type_;
  std::vector<JointInfo> joints_;
  std::vector<ActuatorInfo> actuators_;
};

}  // namespace transmission_interface

#endif  // TRANSMISSION_INTERFACE_TRANSMISSION_INFO_H

// racebot's joint_limits_interface (upstream_compat/joint_limits_interface): ros_control 0.20's API, written for
// racebot. Limits from the parameter server, in MoveIt's joint_limits.yaml layout under <nh>/joint_limits/<joint>:
//   has_position_limits, min_position, max_position, angle_wraparound, has_velocity_limits, max_velocity,
//   has_acceleration_limits, max_acceleration, has_jerk_limits, max_jerk, has_effort_limits, max_effort;
//   has_soft_limits, soft_lower_limit, soft_upper_limit, k_position, k_velocity.
#ifndef JOINT_LIMITS_INTERFACE_JOINT_LIMITS_ROSPARAM_H
#define JOINT_LIMITS_INTERFACE_JOINT_LIMITS_ROSPARAM_H

#include <string>

#include <ros/ros.h>

#include <joint_limits_interface/joint_limits.h>

namespace joint_limits_interface
{

namespace internal
{

// The node handle of <nh>/joint_limits/<joint_name>; false when the namespace is not on the server or not a name.
inline bool jointLimitsNodeHandle(const std::string& joint_name, const ros::NodeHandle& nh, const char* what,
                                  ros::NodeHandle& limits_nh)
{
  try
  {
    const std::string limits_namespace = "joint_limits/" + joint_name;
    if (!nh.hasParam(limits_namespace))
    {
      ROS_DEBUG_STREAM("No " << what << " specification found for joint '" << joint_name
                             << "' in the parameter server (namespace " << nh.getNamespace() + "/" + limits_namespace
                             << ").");
      return false;
    }
    limits_nh = ros::NodeHandle(nh, limits_namespace);
  }
  catch (const ros::InvalidNameException& ex)
  {
    ROS_ERROR_STREAM(ex.what());
    return false;
  }
  return true;
}

// has_<kind>_limits false unsets the limit; true sets it only together with its value (max_<kind>).
inline void readOneLimit(const ros::NodeHandle& limits_nh, const std::string& kind, bool& has_limit, double& max_value)
{
  bool has = false;
  if (!limits_nh.getParam("has_" + kind + "_limits", has))
    return;
  if (!has)
  {
    has_limit = false;
    return;
  }
  double value;
  if (limits_nh.getParam("max_" + kind, value))
  {
    has_limit = true;
    max_value = value;
  }
}

}  // namespace internal

// The limits given under <nh>/joint_limits/<joint_name>; what is not given keeps its value in `limits`. True when
// that namespace exists.
inline bool getJointLimits(const std::string& joint_name, const ros::NodeHandle& nh, JointLimits& limits)
{
  ros::NodeHandle limits_nh;
  if (!internal::jointLimitsNodeHandle(joint_name, nh, "joint limits", limits_nh))
    return false;

  bool has_position_limits = false;
  if (limits_nh.getParam("has_position_limits", has_position_limits))
  {
    if (!has_position_limits)
      limits.has_position_limits = false;
    double min_position, max_position;
    if (has_position_limits && limits_nh.getParam("min_position", min_position) &&
        limits_nh.getParam("max_position", max_position))
    {
      limits.has_position_limits = true;
      limits.min_position = min_position;
      limits.max_position = max_position;
    }
    // only meaningful for a joint without position limits
    bool angle_wraparound;
    if (!has_position_limits && limits_nh.getParam("angle_wraparound", angle_wraparound))
      limits.angle_wraparound = angle_wraparound;
  }

  internal::readOneLimit(limits_nh, "velocity", limits.has_velocity_limits, limits.max_velocity);
  internal::readOneLimit(limits_nh, "acceleration", limits.has_acceleration_limits, limits.max_acceleration);
  internal::readOneLimit(limits_nh, "jerk", limits.has_jerk_limits, limits.max_jerk);
  internal::readOneLimit(limits_nh, "effort", limits.has_effort_limits, limits.max_effort);
  return true;
}

// The soft limits under <nh>/joint_limits/<joint_name>: only a whole specification (has_soft_limits true and all
// four values) is taken, and then the result is true.
inline bool getSoftJointLimits(const std::string& joint_name, const ros::NodeHandle& nh, SoftJointLimits& soft_limits)
{
  ros::NodeHandle limits_nh;
  if (!internal::jointLimitsNodeHandle(joint_name, nh, "soft joint limits", limits_nh))
    return false;

  bool has_soft_limits;
  if (!limits_nh.getParam("has_soft_limits", has_soft_limits) || !has_soft_limits)
    return false;
  if (!limits_nh.hasParam("k_position") || !limits_nh.hasParam("k_velocity") ||
      !limits_nh.hasParam("soft_lower_limit") || !limits_nh.hasParam("soft_upper_limit"))
    return false;
  limits_nh.getParam("k_position", soft_limits.k_position);
  limits_nh.getParam("k_velocity", soft_limits.k_velocity);
  limits_nh.getParam("soft_lower_limit", soft_limits.min_position);
  limits_nh.getParam("soft_upper_limit", soft_limits.max_position);
  return true;
}

}  // namespace joint_limits_interface

#endif  // JOINT_LIMITS_INTERFACE_JOINT_LIMITS_ROSPARAM_H

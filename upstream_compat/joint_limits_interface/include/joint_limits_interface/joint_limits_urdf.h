// racebot's joint_limits_interface (upstream_compat/joint_limits_interface): ros_control 0.20's API, written for
// racebot. Limits from a URDF joint (urdfdom's model, as urdf::Model parses it).
#ifndef JOINT_LIMITS_INTERFACE_JOINT_LIMITS_URDF_H
#define JOINT_LIMITS_INTERFACE_JOINT_LIMITS_URDF_H

#include <ros/common.h>
#include <urdf/urdfdom_compatibility.h>
#include <urdf_model/joint.h>

#include <joint_limits_interface/joint_limits.h>

namespace joint_limits_interface
{

// From the joint's <limit>: position limits for a revolute or prismatic joint (a continuous one wraps around),
// velocity and effort limits always, no acceleration limit. Fields the URDF does not give keep their values. False,
// changing nothing, for a null joint or one without <limit>.
inline bool getJointLimits(urdf::JointConstSharedPtr urdf_joint, JointLimits& limits)
{
  if (!urdf_joint || !urdf_joint->limits)
    return false;

  const bool bounded = urdf_joint->type == urdf::Joint::REVOLUTE || urdf_joint->type == urdf::Joint::PRISMATIC;
  limits.has_position_limits = bounded;
  if (bounded)
  {
    limits.min_position = urdf_joint->limits->lower;
    limits.max_position = urdf_joint->limits->upper;
  }
  else if (urdf_joint->type == urdf::Joint::CONTINUOUS)
  {
    limits.angle_wraparound = true;
  }

  limits.has_velocity_limits = true;
  limits.max_velocity = urdf_joint->limits->velocity;
  limits.has_acceleration_limits = false;
  limits.has_effort_limits = true;
  limits.max_effort = urdf_joint->limits->effort;
  return true;
}

// From the joint's <safety_controller>; false, changing nothing, without one.
inline bool getSoftJointLimits(urdf::JointConstSharedPtr urdf_joint, SoftJointLimits& soft_limits)
{
  if (!urdf_joint || !urdf_joint->safety)
    return false;

  soft_limits.min_position = urdf_joint->safety->soft_lower_limit;
  soft_limits.max_position = urdf_joint->safety->soft_upper_limit;
  soft_limits.k_position = urdf_joint->safety->k_position;
  soft_limits.k_velocity = urdf_joint->safety->k_velocity;
  return true;
}

}  // namespace joint_limits_interface

#endif  // JOINT_LIMITS_INTERFACE_JOINT_LIMITS_URDF_H

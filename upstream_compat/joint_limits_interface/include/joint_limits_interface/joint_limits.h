// racebot's joint_limits_interface (upstream_compat/joint_limits_interface): ros_control 0.20's API, written for
// racebot. A joint's limits, each with a flag saying whether it is set (all unset and 0 by default).
#ifndef JOINT_LIMITS_INTERFACE_JOINT_LIMITS_H
#define JOINT_LIMITS_INTERFACE_JOINT_LIMITS_H

namespace joint_limits_interface
{

struct JointLimits
{
  double min_position = 0.0;
  double max_position = 0.0;
  double max_velocity = 0.0;
  double max_acceleration = 0.0;
  double max_jerk = 0.0;
  double max_effort = 0.0;

  bool has_position_limits = false;
  bool has_velocity_limits = false;
  bool has_acceleration_limits = false;
  bool has_jerk_limits = false;
  bool has_effort_limits = false;
  bool angle_wraparound = false;  // a continuous joint: positions wrap around
};

// A URDF <safety_controller>'s soft limits: positions and the gains that push a joint back inside them.
struct SoftJointLimits
{
  double min_position = 0.0;
  double max_position = 0.0;
  double k_position = 0.0;
  double k_velocity = 0.0;
};

}  // namespace joint_limits_interface

#endif  // JOINT_LIMITS_INTERFACE_JOINT_LIMITS_H

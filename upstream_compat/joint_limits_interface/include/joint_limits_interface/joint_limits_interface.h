// racebot's joint_limits_interface (upstream_compat/joint_limits_interface): ros_control 0.20's API, written for
// racebot. Handles that bring a joint's command within its limits in place (enforceLimits, called by the robot
// hardware between the controllers' update and the write to the joints), and interfaces holding them by joint name.
// Saturation handles clamp to the hard limits; soft-limits handles follow the URDF <safety_controller> rule: near a
// soft position limit, the allowed velocity shrinks in proportion to k_position (and, for efforts, the allowed effort
// in proportion to k_velocity).
#ifndef JOINT_LIMITS_INTERFACE_JOINT_LIMITS_INTERFACE_H
#define JOINT_LIMITS_INTERFACE_JOINT_LIMITS_INTERFACE_H

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <ros/duration.h>

#include <hardware_interface/internal/resource_manager.h>
#include <hardware_interface/joint_command_interface.h>

#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>

namespace joint_limits_interface
{

namespace internal
{

template <typename T>
T saturate(const T val, const T min_val, const T max_val)
{
  return std::min(std::max(val, min_val), max_val);
}

// The velocity range that keeps a joint at `pos` within its soft position limits, within +-max_vel.
inline void softVelocityBounds(const JointLimits& limits, const SoftJointLimits& soft, double max_vel, double pos,
                               double& min_vel_out, double& max_vel_out)
{
  if (limits.has_position_limits)
  {
    min_vel_out = saturate(-soft.k_position * (pos - soft.min_position), -max_vel, max_vel);
    max_vel_out = saturate(-soft.k_position * (pos - soft.max_position), -max_vel, max_vel);
  }
  else  // e.g. a continuous joint
  {
    min_vel_out = -max_vel;
    max_vel_out = max_vel;
  }
}

inline void requireLimit(bool has, const std::string& joint, const char* what)
{
  if (!has)
    throw JointLimitsInterfaceException("Cannot enforce limits for joint '" + joint + "'. It has no " + what +
                                        " limits specification.");
}

}  // namespace internal

// A position command within the position limits and, with a velocity limit, within max_velocity * period of the
// previous command (the joint's position before the first).
class PositionJointSaturationHandle
{
public:
  PositionJointSaturationHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits)
    : jh_(jh), limits_(limits)
  {
    if (limits_.has_position_limits)
    {
      min_pos_limit_ = limits_.min_position;
      max_pos_limit_ = limits_.max_position;
    }
    else
    {
      min_pos_limit_ = -std::numeric_limits<double>::max();
      max_pos_limit_ = std::numeric_limits<double>::max();
    }
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& period)
  {
    if (std::isnan(prev_cmd_))
      prev_cmd_ = jh_.getPosition();

    double min_pos = min_pos_limit_;
    double max_pos = max_pos_limit_;
    if (limits_.has_velocity_limits)
    {
      const double step = limits_.max_velocity * period.toSec();
      min_pos = std::max(prev_cmd_ - step, min_pos_limit_);
      max_pos = std::min(prev_cmd_ + step, max_pos_limit_);
    }
    const double cmd = internal::saturate(jh_.getCommand(), min_pos, max_pos);
    jh_.setCommand(cmd);
    prev_cmd_ = cmd;
  }

  // The next enforceLimits starts again from the joint's position (e.g. after the controllers were switched).
  void reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  double min_pos_limit_;
  double max_pos_limit_;
  double prev_cmd_ = std::numeric_limits<double>::quiet_NaN();
};

// A position command that moves the joint from the previous command at no more than the soft-limit velocity bounds,
// and never beyond the hard position limits. Needs a velocity limit; period must be positive.
class PositionJointSoftLimitsHandle
{
public:
  PositionJointSoftLimitsHandle() = default;

  PositionJointSoftLimitsHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits,
                                const SoftJointLimits& soft_limits)
    : jh_(jh), limits_(limits), soft_limits_(soft_limits)
  {
    internal::requireLimit(limits.has_velocity_limits, getName(), "velocity");
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& period)
  {
    assert(period.toSec() > 0.0);
    // the previous command stands for the position: the joint's own lags behind it
    if (std::isnan(prev_cmd_))
      prev_cmd_ = jh_.getPosition();
    const double pos = prev_cmd_;

    double min_vel, max_vel;
    internal::softVelocityBounds(limits_, soft_limits_, limits_.max_velocity, pos, min_vel, max_vel);

    const double dt = period.toSec();
    double pos_low = pos + min_vel * dt;
    double pos_high = pos + max_vel * dt;
    if (limits_.has_position_limits)
    {
      // a soft limit set beyond the hard one must not let the command past the hard one
      pos_low = std::max(pos_low, limits_.min_position);
      pos_high = std::min(pos_high, limits_.max_position);
    }

    jh_.setCommand(internal::saturate(jh_.getCommand(), pos_low, pos_high));
    prev_cmd_ = jh_.getCommand();
  }

  void reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
  double prev_cmd_ = std::numeric_limits<double>::quiet_NaN();
};

// An effort command within +-max_effort, and none that pushes further out of the position limits or past the
// velocity limit. Needs velocity and effort limits.
class EffortJointSaturationHandle
{
public:
  EffortJointSaturationHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits)
    : jh_(jh), limits_(limits)
  {
    internal::requireLimit(limits.has_velocity_limits, getName(), "velocity");
    internal::requireLimit(limits.has_effort_limits, getName(), "efforts");
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& /*period*/)
  {
    double min_eff = -limits_.max_effort;
    double max_eff = limits_.max_effort;

    if (limits_.has_position_limits)
    {
      const double pos = jh_.getPosition();
      if (pos < limits_.min_position)
        min_eff = 0.0;
      else if (pos > limits_.max_position)
        max_eff = 0.0;
    }

    const double vel = jh_.getVelocity();
    if (vel < -limits_.max_velocity)
      min_eff = 0.0;
    else if (vel > limits_.max_velocity)
      max_eff = 0.0;

    jh_.setCommand(internal::saturate(jh_.getCommand(), min_eff, max_eff));
  }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
};

// An effort command within the bounds that drive the joint's velocity towards the soft-limit velocity bounds
// (gain k_velocity), within +-max_effort. Needs velocity and effort limits.
class EffortJointSoftLimitsHandle
{
public:
  EffortJointSoftLimitsHandle() = default;

  EffortJointSoftLimitsHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits,
                              const SoftJointLimits& soft_limits)
    : jh_(jh), limits_(limits), soft_limits_(soft_limits)
  {
    internal::requireLimit(limits.has_velocity_limits, getName(), "velocity");
    internal::requireLimit(limits.has_effort_limits, getName(), "effort");
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& /*period*/)
  {
    using internal::saturate;
    const double pos = jh_.getPosition();
    const double vel = jh_.getVelocity();

    double min_vel, max_vel;
    internal::softVelocityBounds(limits_, soft_limits_, limits_.max_velocity, pos, min_vel, max_vel);

    const double min_eff = saturate(-soft_limits_.k_velocity * (vel - min_vel), -limits_.max_effort, limits_.max_effort);
    const double max_eff = saturate(-soft_limits_.k_velocity * (vel - max_vel), -limits_.max_effort, limits_.max_effort);
    jh_.setCommand(saturate(jh_.getCommand(), min_eff, max_eff));
  }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
};

// A velocity command within +-max_velocity and, with an acceleration limit, within max_acceleration * period of the
// previous command (0 before the first). Needs a velocity limit.
class VelocityJointSaturationHandle
{
public:
  VelocityJointSaturationHandle() = default;

  VelocityJointSaturationHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits)
    : jh_(jh), limits_(limits)
  {
    internal::requireLimit(limits.has_velocity_limits, getName(), "velocity");
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& period)
  {
    double vel_low = -limits_.max_velocity;
    double vel_high = limits_.max_velocity;
    if (limits_.has_acceleration_limits)
    {
      assert(period.toSec() > 0.0);
      const double step = limits_.max_acceleration * period.toSec();
      vel_low = std::max(prev_cmd_ - step, -limits_.max_velocity);
      vel_high = std::min(prev_cmd_ + step, limits_.max_velocity);
    }
    jh_.setCommand(internal::saturate(jh_.getCommand(), vel_low, vel_high));
    prev_cmd_ = jh_.getCommand();
  }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  double prev_cmd_ = 0.0;
};

// A velocity command within the soft-limit velocity bounds at the joint's position (within +-max_velocity when it
// has one) and, with an acceleration limit, within max_acceleration * period of the joint's velocity.
class VelocityJointSoftLimitsHandle
{
public:
  VelocityJointSoftLimitsHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits,
                                const SoftJointLimits& soft_limits)
    : jh_(jh), limits_(limits), soft_limits_(soft_limits)
  {
    max_vel_limit_ = limits.has_velocity_limits ? limits.max_velocity : std::numeric_limits<double>::max();
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& period)
  {
    double min_vel, max_vel;
    internal::softVelocityBounds(limits_, soft_limits_, max_vel_limit_, jh_.getPosition(), min_vel, max_vel);
    if (limits_.has_acceleration_limits)
    {
      const double vel = jh_.getVelocity();
      const double step = limits_.max_acceleration * period.toSec();
      min_vel = std::max(vel - step, min_vel);
      max_vel = std::min(vel + step, max_vel);
    }
    jh_.setCommand(internal::saturate(jh_.getCommand(), min_vel, max_vel));
  }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
  double max_vel_limit_;
};

// Limits handles by joint name. Not a hardware interface a controller claims: the robot hardware holds it.
template <class HandleType>
class JointLimitsInterface : public hardware_interface::ResourceManager<HandleType>
{
public:
  // JointLimitsInterfaceException when there is no handle of that name.
  HandleType getHandle(const std::string& name)
  {
    try
    {
      return this->hardware_interface::ResourceManager<HandleType>::getHandle(name);
    }
    catch (const std::logic_error& e)
    {
      throw JointLimitsInterfaceException(e.what());
    }
  }

  // Every handle's enforceLimits(period).
  void enforceLimits(const ros::Duration& period)
  {
    for (auto& entry : this->resource_map_)
      entry.second.enforceLimits(period);
  }
};

class PositionJointSaturationInterface : public JointLimitsInterface<PositionJointSaturationHandle>
{
public:
  void reset()
  {
    for (auto& entry : this->resource_map_)
      entry.second.reset();
  }
};

class PositionJointSoftLimitsInterface : public JointLimitsInterface<PositionJointSoftLimitsHandle>
{
public:
  void reset()
  {
    for (auto& entry : this->resource_map_)
      entry.second.reset();
  }
};

class EffortJointSaturationInterface : public JointLimitsInterface<EffortJointSaturationHandle>
{
};
class EffortJointSoftLimitsInterface : public JointLimitsInterface<EffortJointSoftLimitsHandle>
{
};
class VelocityJointSaturationInterface : public JointLimitsInterface<VelocityJointSaturationHandle>
{
};
class VelocityJointSoftLimitsInterface : public JointLimitsInterface<VelocityJointSoftLimitsHandle>
{
};

}  // namespace joint_limits_interface

#endif  // JOINT_LIMITS_INTERFACE_JOINT_LIMITS_INTERFACE_H

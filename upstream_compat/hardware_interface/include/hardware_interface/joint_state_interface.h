// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
// A joint's state read through pointers into the hardware's own storage.
#ifndef HARDWARE_INTERFACE_JOINT_STATE_INTERFACE_H
#define HARDWARE_INTERFACE_JOINT_STATE_INTERFACE_H

#include <cassert>
#include <stdexcept>
#include <string>

#include <hardware_interface/internal/hardware_resource_manager.h>

namespace hardware_interface
{

class JointStateHandle
{
public:
  JointStateHandle() = default;

  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff)
    : name_(name), pos_(pos), vel_(vel), eff_(eff)
  {
    requireState();
  }

  // With an absolute encoder and a torque sensor.
  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff,
                   const double* absolute_pos, const double* torque_sensor)
    : name_(name), pos_(pos), vel_(vel), eff_(eff), absolute_pos_(absolute_pos), torque_sensor_(torque_sensor)
  {
    requireState();
    require(absolute_pos, "Absolute");
    require(torque_sensor, "Torque sensor");
  }

  // With an absolute encoder.
  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff,
                   const double* absolute_pos)
    : name_(name), pos_(pos), vel_(vel), eff_(eff), absolute_pos_(absolute_pos)
  {
    requireState();
    require(absolute_pos, "Absolute");
  }

  // With a torque sensor (the bool only tells this constructor from the one above).
  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff,
                   const double* torque_sensor, bool)
    : name_(name), pos_(pos), vel_(vel), eff_(eff), torque_sensor_(torque_sensor)
  {
    requireState();
    require(torque_sensor, "Torque sensor");
  }

  std::string getName() const { return name_; }
  double getPosition() const
  {
    assert(pos_);
    return *pos_;
  }
  double getVelocity() const
  {
    assert(vel_);
    return *vel_;
  }
  double getEffort() const
  {
    assert(eff_);
    return *eff_;
  }
  double getAbsolutePosition() const { return *getAbsolutePositionPtr(); }
  double getTorqueSensor() const { return *getTorqueSensorPtr(); }

  const double* getPositionPtr() const { return pos_; }
  const double* getVelocityPtr() const { return vel_; }
  const double* getEffortPtr() const { return eff_; }
  const double* getAbsolutePositionPtr() const
  {
    if (!hasAbsolutePosition())
      throw std::runtime_error("Joint state handle does not contain absolute encoder position information");
    return absolute_pos_;
  }
  const double* getTorqueSensorPtr() const
  {
    if (!hasTorqueSensor())
      throw std::runtime_error("Joint state handle does not contain torque sensor information");
    return torque_sensor_;
  }

  bool hasAbsolutePosition() const { return absolute_pos_ != nullptr; }
  bool hasTorqueSensor() const { return torque_sensor_ != nullptr; }

private:
  void require(const double* data, const char* what) const
  {
    if (!data)
      throw HardwareInterfaceException("Cannot create handle '" + name_ + "'. " + what + " data pointer is null.");
  }
  void requireState() const
  {
    require(pos_, "Position");
    require(vel_, "Velocity");
    require(eff_, "Effort");
  }

  std::string name_;
  const double* pos_ = nullptr;
  const double* vel_ = nullptr;
  const double* eff_ = nullptr;
  const double* absolute_pos_ = nullptr;
  const double* torque_sensor_ = nullptr;
};

// Reading joint states claims nothing: any number of controllers may read a joint.
class JointStateInterface : public HardwareResourceManager<JointStateHandle>
{
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_JOINT_STATE_INTERFACE_H

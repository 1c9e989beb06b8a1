// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
// A force-torque sensor's readings through pointers into the hardware's storage.
#ifndef HARDWARE_INTERFACE_FORCE_TORQUE_SENSOR_INTERFACE_H
#define HARDWARE_INTERFACE_FORCE_TORQUE_SENSOR_INTERFACE_H

#include <string>

#include <hardware_interface/internal/hardware_resource_manager.h>

namespace hardware_interface
{

class ForceTorqueSensorHandle
{
public:
  ForceTorqueSensorHandle() = default;
  // force and torque: x, y, z each, in frame_id
  ForceTorqueSensorHandle(const std::string& name, const std::string& frame_id, const double* force,
                          const double* torque)
    : name_(name), frame_id_(frame_id), force_(force), torque_(torque)
  {
  }

  std::string getName() const { return name_; }
  std::string getFrameId() const { return frame_id_; }
  const double* getForce() const { return force_; }
  const double* getTorque() const { return torque_; }

private:
  std::string name_;
  std::string frame_id_;
  const double* force_ = nullptr;
  const double* torque_ = nullptr;
};

class ForceTorqueSensorInterface : public HardwareResourceManager<ForceTorqueSensorHandle>
{
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_FORCE_TORQUE_SENSOR_INTERFACE_H

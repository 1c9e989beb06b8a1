// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): sensors::ImuSensor (a <sensor type="imu">), as
// gazebo/sensors/ImuSensor.hh has it. One measurement of racebot's (gazebo_plugins/compiled_sensors.py, with
// Gazebo's ImuSensor::UpdateImpl arithmetic: the link's angular velocity in the sensor frame; the sensor point's
// velocity differenced since the previous measurement, minus gravity, in the sensor frame; the <imu> element's
// per-axis <noise> on the values a plugin reads by default, the noise-free ones kept) is published as a msgs::IMU
// on "~/<model>/<link>/<sensor>/imu" to transport subscribers. The orientation is the sensor frame's relative to
// the reference, which is the sensor's orientation when it was made (Gazebo's default: a plugin that wants the
// world as reference, REP 145, calls SetWorldToReferenceOrientation(Quaterniond::Identity), as gazebo_ros_imu_sensor
// does). The <imu><orientation_reference_frame> element is not read.
#ifndef GAZEBO_SENSORS_IMUSENSOR_HH_
#define GAZEBO_SENSORS_IMUSENSOR_HH_

#include <string>

#include <ignition/math/Pose3.hh>
#include <ignition/math/Quaternion.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/sensors/Sensor.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace sensors
{
class GZ_SENSORS_VISIBLE ImuSensor : public Sensor
{
public:
  // racebot's host: the sensor's link (Description::parentName, model::link) is in physics::get_world(); a
  // std::runtime_error otherwise, with Gazebo's words ("IMU has invalid parent[...]. Must be a link")
  explicit ImuSensor(const Description &_description);

  msgs::IMU ImuMessage() const;
  // in the sensor frame; by default with the sensor's <noise>, `_noiseFree`: without
  ignition::math::Vector3d AngularVelocity(const bool _noiseFree = false) const;
  ignition::math::Vector3d LinearAcceleration(const bool _noiseFree = false) const;
  // the sensor frame's orientation relative to the reference frame, at the last measurement
  ignition::math::Quaterniond Orientation() const;
  // the sensor's orientation now becomes the reference
  void SetReferencePose();
  void SetWorldToReferenceOrientation(const ignition::math::Quaterniond &_orientation);
  // active, or somebody subscribes to its imu topic (Gazebo's ImuSensor::IsActive)
  bool IsActive() const override;

  // racebot's host: one measurement at sim time `_time` with the sensor frame at `_worldPose`: the noise-free
  // angular velocity and linear acceleration (sensor frame) and the same with the sensor's noise. Publishes the
  // msgs::IMU to its subscribers, then fires the updated event.
  void Measure(const common::Time &_time, const ignition::math::Pose3d &_worldPose,
               const ignition::math::Vector3d &_angularVel, const ignition::math::Vector3d &_linearAcc,
               const ignition::math::Vector3d &_noisyAngularVel, const ignition::math::Vector3d &_noisyLinearAcc);

private:
  // the sensor frame's world pose now, from its link
  ignition::math::Pose3d WorldPose() const;

  physics::LinkPtr parent;
  msgs::IMU imuMsg;
  ignition::math::Vector3d angularVel;
  ignition::math::Vector3d linearAcc;
  ignition::math::Quaterniond worldToReference;
  const std::string imuTopic;  // decoded, /gazebo/<world>/<model>/<link>/<sensor>/imu
};
}  // namespace sensors
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): sensors::Sensor, what a sensor plugin's Load gets.
// racebot's world server makes one for each <sensor> that carries a compiled plugin and measures it with its own
// simulator at the sensor's update rate, while IsActive() (gazebo_plugins/compiled_sensors.py): each measurement
// sets LastMeasurementTime and LastUpdateTime to the sim time of the step and fires the updated event
// (ConnectUpdated), as Gazebo's Sensor::Update after UpdateImpl.
#ifndef GAZEBO_SENSORS_SENSOR_HH_
#define GAZEBO_SENSORS_SENSOR_HH_

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <ignition/math/Pose3.hh>
#include <sdf/sdf.hh>

// what Gazebo's Sensor.hh brings: a sensor plugin that includes only ImuSensor.hh and World.hh connects to
// event::Events (gazebo_ros_imu_sensor)
#include "gazebo/common/Event.hh"
#include "gazebo/common/Events.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/sensors/SensorTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace sensors
{
class GZ_SENSORS_VISIBLE Sensor : public std::enable_shared_from_this<Sensor>
{
public:
  // racebot's host: what Gazebo reads of the <sensor> element and where it is mounted
  struct Description
  {
    std::string name;
    std::string type;        // "ray", "gpu_ray", ...
    std::string parentName;  // the scoped name of its link, model::link
    std::string worldName;
    uint32_t id = 0;
    uint32_t parentId = 0;
    ignition::math::Pose3d pose;  // in its link
    double updateRate = 0.0;      // Hz; 0: every update
    bool alwaysOn = false;
    bool visualize = false;
  };

  Sensor(const Description &_description, SensorCategory _category);
  virtual ~Sensor();

  virtual void Init() {}
  virtual void Fini() {}
  std::string Name() const { return this->description.name; }
  // world::model::link::sensor
  std::string ScopedName() const;
  std::string ParentName() const { return this->description.parentName; }
  uint32_t Id() const { return this->description.id; }
  uint32_t ParentId() const { return this->description.parentId; }
  std::string Type() const { return this->description.type; }
  std::string WorldName() const { return this->description.worldName; }
  SensorCategory Category() const { return this->category; }
  double UpdateRate() const;
  void SetUpdateRate(const double _hz);
  virtual ignition::math::Pose3d Pose() const;
  virtual void SetPose(const ignition::math::Pose3d &_pose);
  virtual void SetActive(const bool _value);
  virtual bool IsActive() const;
  common::Time LastUpdateTime() const;
  common::Time LastMeasurementTime() const;
  bool Visualize() const { return this->description.visualize; }
  // "" here; a RaySensor's is its scan topic
  virtual std::string Topic() const { return ""; }
  event::ConnectionPtr ConnectUpdated(std::function<void()> _subscriber);
  void ResetLastUpdateTime();

  // racebot's host: a measurement of sim time `_time` was made (the subclass set its data): the times, then the
  // updated event
  void Measured(const common::Time &_time);

protected:
  Description description;
  SensorCategory category;
  mutable std::mutex mutex;
  bool active;
  common::Time lastUpdateTime;
  common::Time lastMeasurementTime;
  event::EventT<void()> updated;
};
}  // namespace sensors
}  // namespace gazebo

#endif

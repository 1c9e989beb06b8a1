// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the sensor pointer types (std::shared_ptr, as Gazebo
// 11's) and categories. What racebot hosts: Sensor.hh, RaySensor.hh, GpuRaySensor.hh, ImuSensor.hh, ContactSensor.hh, CameraSensor.hh (docs/SUPPORTED.md).
#ifndef GAZEBO_SENSORS_SENSORTYPES_HH_
#define GAZEBO_SENSORS_SENSORTYPES_HH_

#include <memory>
#include <vector>

namespace gazebo
{
namespace sensors
{
class Sensor;
class RaySensor;
class GpuRaySensor;
class CameraSensor;
class DepthCameraSensor;
class MultiCameraSensor;
class ContactSensor;
class ImuSensor;
class GpsSensor;
class SonarSensor;
class ForceTorqueSensor;
class MagnetometerSensor;
class AltimeterSensor;
typedef std::shared_ptr<Sensor> SensorPtr;
typedef std::shared_ptr<RaySensor> RaySensorPtr;
typedef std::shared_ptr<GpuRaySensor> GpuRaySensorPtr;
typedef std::shared_ptr<CameraSensor> CameraSensorPtr;
typedef std::shared_ptr<DepthCameraSensor> DepthCameraSensorPtr;
typedef std::shared_ptr<MultiCameraSensor> MultiCameraSensorPtr;
typedef std::shared_ptr<ContactSensor> ContactSensorPtr;
typedef std::shared_ptr<ImuSensor> ImuSensorPtr;
typedef std::shared_ptr<GpsSensor> GpsSensorPtr;
typedef std::shared_ptr<SonarSensor> SonarSensorPtr;
typedef std::shared_ptr<ForceTorqueSensor> ForceTorqueSensorPtr;
typedef std::shared_ptr<MagnetometerSensor> MagnetometerSensorPtr;
typedef std::shared_ptr<AltimeterSensor> AltimeterSensorPtr;
typedef std::vector<SensorPtr> Sensor_V;

// Gazebo's: a plugin writes `GAZEBO_SENSORS_USING_DYNAMIC_POINTER_CAST; dynamic_pointer_cast<...>(_parent)`
#define GAZEBO_SENSORS_USING_DYNAMIC_POINTER_CAST using std::dynamic_pointer_cast

enum SensorCategory
{
  IMAGE = 0,
  RAY = 1,
  OTHER = 2,
  CATEGORY_COUNT = 3
};
}  // namespace sensors
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the sensor pointer types SensorPlugin names.
// racebot does not host compiled sensor plugins yet (docs/SUPPORTED.md).
#ifndef GAZEBO_SENSORS_SENSORTYPES_HH_
#define GAZEBO_SENSORS_SENSORTYPES_HH_

#include <memory>

namespace gazebo
{
namespace sensors
{
class Sensor;
typedef std::shared_ptr<Sensor> SensorPtr;
}  // namespace sensors
}  // namespace gazebo

#endif

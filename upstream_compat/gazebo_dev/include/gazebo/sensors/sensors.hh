// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): what `#include <gazebo/sensors/sensors.hh>` gives
// of what racebot has.
#ifndef GAZEBO_SENSORS_SENSORS_HH_
#define GAZEBO_SENSORS_SENSORS_HH_

#include "gazebo/sensors/CameraSensor.hh"
#include "gazebo/sensors/ContactSensor.hh"
#include "gazebo/sensors/GpuRaySensor.hh"
#include "gazebo/sensors/ImuSensor.hh"
#include "gazebo/sensors/RaySensor.hh"
#include "gazebo/sensors/Sensor.hh"
#include "gazebo/sensors/SensorTypes.hh"

#endif

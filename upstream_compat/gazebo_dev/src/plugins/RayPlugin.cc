// racebot's Gazebo 11 plugin API: libRayPlugin, Gazebo's RayPlugin (plugins/RayPlugin.hh).
#include "gazebo/plugins/RayPlugin.hh"

#include <functional>

namespace gazebo
{
RayPlugin::RayPlugin() = default;

RayPlugin::~RayPlugin()
{
  this->newLaserScansConnection.reset();
  this->parentSensor.reset();
  this->world.reset();
}

void RayPlugin::OnNewLaserScans() {}

void RayPlugin::Load(sensors::SensorPtr _parent, sdf::ElementPtr /*_sdf*/)
{
  this->parentSensor = std::dynamic_pointer_cast<sensors::RaySensor>(_parent);
  if (!this->parentSensor)
    gzthrow("RayPlugin requires a Ray Sensor as its parent");
  this->world = physics::get_world(this->parentSensor->WorldName());
  this->newLaserScansConnection =
    this->parentSensor->LaserShape()->ConnectNewLaserScans(std::bind(&RayPlugin::OnNewLaserScans, this));
}
}  // namespace gazebo

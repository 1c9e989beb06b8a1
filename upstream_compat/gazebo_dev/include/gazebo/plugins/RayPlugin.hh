// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): Gazebo's RayPlugin (library libRayPlugin), the base
// of ray sensor plugins (velodyne_gazebo_plugins' GazeboRosVelodyneLaser): Load keeps the parent RaySensor (gzthrow
// when it is another kind) and the world, and connects OnNewLaserScans to its laser shape's new scans.
#ifndef GAZEBO_PLUGINS_RAYPLUGIN_HH_
#define GAZEBO_PLUGINS_RAYPLUGIN_HH_

#include "gazebo/common/Plugin.hh"
#include "gazebo/physics/World.hh"
#include "gazebo/sensors/RaySensor.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
class GZ_PLUGIN_VISIBLE RayPlugin : public SensorPlugin
{
public:
  RayPlugin();
  virtual ~RayPlugin();
  virtual void OnNewLaserScans();
  void Load(sensors::SensorPtr _parent, sdf::ElementPtr _sdf);

protected:
  physics::WorldPtr world;

private:
  sensors::RaySensorPtr parentSensor;
  event::ConnectionPtr newLaserScansConnection;
};
}  // namespace gazebo

#endif

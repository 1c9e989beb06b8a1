// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): Gazebo's GpuRayPlugin (library libGpuRayPlugin), the
// base of gpu_ray sensor plugins: Load keeps the parent GpuRaySensor (gzthrow when it is another kind), its range
// counts as width and height, and connects OnNewLaserFrame to its laser frames.
#ifndef GAZEBO_PLUGINS_GPURAYPLUGIN_HH_
#define GAZEBO_PLUGINS_GPURAYPLUGIN_HH_

#include <string>

#include "gazebo/common/Plugin.hh"
#include "gazebo/sensors/GpuRaySensor.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
class GZ_PLUGIN_VISIBLE GpuRayPlugin : public SensorPlugin
{
public:
  GpuRayPlugin();
  virtual ~GpuRayPlugin();
  virtual void OnNewLaserFrame(const float *_image, unsigned int _width, unsigned int _height, unsigned int _depth,
                               const std::string &_format);
  void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf);

protected:
  unsigned int width = 0;
  unsigned int height = 0;
  sensors::GpuRaySensorPtr parentSensor;
  event::ConnectionPtr newLaserFrameConnection;
};
}  // namespace gazebo

#endif

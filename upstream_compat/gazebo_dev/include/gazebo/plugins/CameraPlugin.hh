// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): Gazebo's CameraPlugin (library libCameraPlugin), the
// base of camera sensor plugins (gazebo_plugins' GazeboRosCamera, hector's thermal camera): Load keeps the parent
// CameraSensor and its camera (gzthrow when it is another kind), the image's width, height, depth and format,
// connects OnNewFrame to the camera's new frames and switches the sensor on.
#ifndef GAZEBO_PLUGINS_CAMERAPLUGIN_HH_
#define GAZEBO_PLUGINS_CAMERAPLUGIN_HH_

#include <string>

#include "gazebo/common/Plugin.hh"
#include "gazebo/rendering/Camera.hh"
#include "gazebo/sensors/CameraSensor.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
class GZ_PLUGIN_VISIBLE CameraPlugin : public SensorPlugin
{
public:
  CameraPlugin();
  virtual ~CameraPlugin();
  virtual void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf);
  virtual void OnNewFrame(const unsigned char *_image, unsigned int _width, unsigned int _height, unsigned int _depth,
                          const std::string &_format);

protected:
  unsigned int width = 0;
  unsigned int height = 0;
  unsigned int depth = 0;
  std::string format;
  sensors::CameraSensorPtr parentSensor;
  rendering::CameraPtr camera;

private:
  event::ConnectionPtr newFrameConnection;
};
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API: libCameraPlugin, Gazebo's CameraPlugin (plugins/CameraPlugin.hh).
#include "gazebo/plugins/CameraPlugin.hh"

#include <functional>

namespace gazebo
{
CameraPlugin::CameraPlugin() = default;

CameraPlugin::~CameraPlugin()
{
  this->newFrameConnection.reset();
  this->parentSensor.reset();
  this->camera.reset();
}

void CameraPlugin::OnNewFrame(const unsigned char * /*_image*/, unsigned int /*_width*/, unsigned int /*_height*/,
                              unsigned int /*_depth*/, const std::string & /*_format*/)
{
}

void CameraPlugin::Load(sensors::SensorPtr _sensor, sdf::ElementPtr /*_sdf*/)
{
  this->parentSensor = std::dynamic_pointer_cast<sensors::CameraSensor>(_sensor);
  if (!this->parentSensor)
    gzthrow("CameraPlugin requires a CameraSensor as its parent");  // Gazebo's says so, then crashes
  this->camera = this->parentSensor->Camera();
  this->width = this->camera->ImageWidth();
  this->height = this->camera->ImageHeight();
  this->depth = this->camera->ImageDepth();
  this->format = this->camera->ImageFormat();
  this->newFrameConnection = this->camera->ConnectNewImageFrame(
      [this](const unsigned char *_image, unsigned int _width, unsigned int _height, unsigned int _depth,
             const std::string &_format) { this->OnNewFrame(_image, _width, _height, _depth, _format); });
  this->parentSensor->SetActive(true);
}
}  // namespace gazebo

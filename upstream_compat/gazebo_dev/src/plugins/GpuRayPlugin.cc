// racebot's Gazebo 11 plugin API: libGpuRayPlugin, Gazebo's GpuRayPlugin (plugins/GpuRayPlugin.hh).
#include "gazebo/plugins/GpuRayPlugin.hh"

#include <functional>

namespace gazebo
{
GpuRayPlugin::GpuRayPlugin() = default;

GpuRayPlugin::~GpuRayPlugin()
{
  this->newLaserFrameConnection.reset();
  this->parentSensor.reset();
}

void GpuRayPlugin::OnNewLaserFrame(const float * /*_image*/, unsigned int /*_width*/, unsigned int /*_height*/,
                                   unsigned int /*_depth*/, const std::string & /*_format*/)
{
}

void GpuRayPlugin::Load(sensors::SensorPtr _sensor, sdf::ElementPtr /*_sdf*/)
{
  this->parentSensor = std::dynamic_pointer_cast<sensors::GpuRaySensor>(_sensor);
  if (!this->parentSensor)
    gzthrow("GpuRayPlugin not attached to a GpuLaser sensor\n");
  this->width = this->parentSensor->RangeCount();
  this->height = this->parentSensor->VerticalRangeCount();
  using std::placeholders::_1;
  using std::placeholders::_2;
  using std::placeholders::_3;
  using std::placeholders::_4;
  using std::placeholders::_5;
  this->newLaserFrameConnection = this->parentSensor->ConnectNewLaserFrame(
    std::bind(&GpuRayPlugin::OnNewLaserFrame, this, _1, _2, _3, _4, _5));
}
}  // namespace gazebo

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): sensors::CameraSensor (a <sensor type="camera">), as
// gazebo/sensors/CameraSensor.hh has it: its rendering::Camera (the image a plugin reads and the new-frame event) and
// the image's size and data. racebot renders a frame at the sensor's update rate while it IsActive() (<always_on>,
// SetActive: CameraPlugin's Load switches it on), from the physics world as the step left it
// (gazebo_plugins/compiled_sensors.py), then fires the camera's new-frame event and the sensor's updated event.
// The image is not published on Gazebo transport (no msgs::ImageStamped here).
#ifndef GAZEBO_SENSORS_CAMERASENSOR_HH_
#define GAZEBO_SENSORS_CAMERASENSOR_HH_

#include <string>
#include <vector>

#include "gazebo/rendering/Camera.hh"
#include "gazebo/rendering/RenderTypes.hh"
#include "gazebo/sensors/Sensor.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace sensors
{
class GZ_SENSORS_VISIBLE CameraSensor : public Sensor
{
public:
  // racebot's host: `_camera` its camera
  CameraSensor(const Description &_description, rendering::CameraPtr _camera);

  rendering::CameraPtr Camera() const { return this->camera; }
  unsigned int ImageWidth() const { return this->camera->ImageWidth(); }
  unsigned int ImageHeight() const { return this->camera->ImageHeight(); }
  const unsigned char *ImageData() const { return this->camera->ImageData(); }
  // "~/<model>/<link>/<sensor>/image", where Gazebo advertises the image
  std::string Topic() const override;
  bool Rendered() const;

  // racebot's host: one frame at sim time `_time`, the camera at `_worldPose`: the camera's new-frame event, then
  // the sensor's updated event
  void Measure(const common::Time &_time, const ignition::math::Pose3d &_worldPose, std::vector<unsigned char> _data);

private:
  rendering::CameraPtr camera;
  bool rendered = false;
};
}  // namespace sensors
}  // namespace gazebo

#endif

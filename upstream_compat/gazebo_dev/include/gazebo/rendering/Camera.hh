// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): rendering::Camera, what a camera sensor plugin reads of
// its camera: the image (size, format, bytes per pixel, the last frame's data), its geometry (fields of view,
// clip distances, world pose at the last frame) and the new-frame event Gazebo fires after each render
// (ConnectNewImageFrame: CameraPlugin::OnNewFrame). racebot renders the frames (gazebo_plugins/compiled_sensors.py)
// and hands them over (the host's Frame); there is no OGRE scene behind it.
#ifndef GAZEBO_RENDERING_CAMERA_HH_
#define GAZEBO_RENDERING_CAMERA_HH_

#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <ignition/math/Angle.hh>
#include <ignition/math/Pose3.hh>

#include "gazebo/common/Event.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/rendering/Distortion.hh"
#include "gazebo/rendering/RenderTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace rendering
{
class GZ_RENDERING_VISIBLE Camera
{
public:
  typedef std::function<void(const unsigned char *, unsigned int, unsigned int, unsigned int, const std::string &)>
      NewFrameCallback;

  // racebot's host: the camera of a <camera> element (its <image>, <horizontal_fov>, <clip>, <distortion>: null
  // distortion for none)
  Camera(const std::string &_name, const std::string &_scopedName, unsigned int _width, unsigned int _height,
         const std::string &_format, double _hfov, double _near, double _far, DistortionPtr _distortion);
  virtual ~Camera() = default;

  std::string Name() const { return this->name; }
  std::string ScopedName() const { return this->scopedName; }
  bool IsInitialized() const { return true; }
  unsigned int ImageWidth() const { return this->width; }
  unsigned int ImageHeight() const { return this->height; }
  // bytes per pixel of the format, as Gazebo's Camera::ImageDepth (3 for a format it does not know, with its error)
  unsigned int ImageDepth() const;
  std::string ImageFormat() const { return this->format; }
  unsigned int ImageByteSize() const;
  static unsigned int ImageByteSize(unsigned int _width, unsigned int _height, const std::string &_format);
  // the last frame (null before the first)
  const unsigned char *ImageData(const unsigned int _i = 0) const;
  ignition::math::Angle HFOV() const;
  // from the horizontal field of view and the aspect ratio, as Gazebo works it out
  ignition::math::Angle VFOV() const;
  // takes effect for the next frame
  void SetHFOV(const ignition::math::Angle &_angle);
  double NearClip() const { return this->nearClip; }
  double FarClip() const { return this->farClip; }
  ignition::math::Pose3d WorldPose() const;
  ignition::math::Vector3d WorldPosition() const { return this->WorldPose().Pos(); }
  ignition::math::Quaterniond WorldRotation() const { return this->WorldPose().Rot(); }
  double RenderRate() const;
  void SetRenderRate(const double _hz);
  void SetCaptureData(const bool _value) { this->captureData = _value; }
  bool CaptureData() const { return this->captureData; }
  DistortionPtr LensDistortion() const { return this->distortion; }
  event::ConnectionPtr ConnectNewImageFrame(NewFrameCallback _subscriber);
  void DisconnectNewImageFrame(event::ConnectionPtr &_c) { _c.reset(); }

  // racebot's host: a frame (ImageByteSize() bytes in ImageFormat()) rendered with the camera at `_worldPose`:
  // kept as ImageData(), then the new-frame event
  void Frame(const ignition::math::Pose3d &_worldPose, std::vector<unsigned char> _data);

private:
  const std::string name;
  const std::string scopedName;
  const unsigned int width;
  const unsigned int height;
  const std::string format;
  double hfov;
  const double nearClip;
  const double farClip;
  DistortionPtr distortion;
  double renderRate = 0.0;
  bool captureData = false;
  mutable std::mutex mutex;
  ignition::math::Pose3d pose;
  std::vector<unsigned char> data;
  event::EventT<void(const unsigned char *, unsigned int, unsigned int, unsigned int, const std::string &)>
      newImageFrame;
};
}  // namespace rendering
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API: rendering::Camera, a camera's image and geometry; its frames come from racebot's
// host (Frame), rendered by racebot's simulator. ImageDepth and ImageByteSize follow gazebo/rendering/Camera.cc.
#include <cmath>
#include <utility>

#include "gazebo/common/Console.hh"
#include "gazebo/rendering/Camera.hh"

namespace gazebo
{
namespace rendering
{
namespace
{
// bytes per pixel of an image format, 0 for one Gazebo does not know
unsigned int FormatDepth(const std::string &_format)
{
  if (_format == "L8" || _format == "L_INT8")
    return 1;
  if (_format == "L16" || _format == "L_INT16")
    return 2;
  if (_format == "R8G8B8" || _format == "RGB_INT8" || _format == "B8G8R8" || _format == "BGR_INT8")
    return 3;
  if (_format == "R16G16B16" || _format == "RGB_INT16")
    return 6;
  if (_format == "BAYER_RGGB8" || _format == "BAYER_BGGR8" || _format == "BAYER_GBRG8" || _format == "BAYER_GRBG8")
    return 1;
  return 0;
}
}  // namespace

Camera::Camera(const std::string &_name, const std::string &_scopedName, unsigned int _width, unsigned int _height,
               const std::string &_format, double _hfov, double _near, double _far, DistortionPtr _distortion)
  : name(_name), scopedName(_scopedName), width(_width), height(_height), format(_format), hfov(_hfov),
    nearClip(_near), farClip(_far), distortion(std::move(_distortion))
{
}

unsigned int Camera::ImageDepth() const
{
  const unsigned int depth = FormatDepth(this->format);
  if (depth == 0)
  {
    gzerr << "Error parsing image format (" << this->format << "), using default Ogre::PF_R8G8B8\n";
    return 3;
  }
  return depth;
}

unsigned int Camera::ImageByteSize() const { return this->width * this->height * this->ImageDepth(); }

unsigned int Camera::ImageByteSize(unsigned int _width, unsigned int _height, const std::string &_format)
{
  const unsigned int depth = FormatDepth(_format);
  return _width * _height * (depth == 0 ? 3 : depth);
}

const unsigned char *Camera::ImageData(const unsigned int _i) const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  if (_i != 0)
  {
    gzerr << "Camera index must be zero for cam\n";
    return nullptr;
  }
  return this->data.empty() ? nullptr : this->data.data();
}

ignition::math::Angle Camera::HFOV() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return ignition::math::Angle(this->hfov);
}

ignition::math::Angle Camera::VFOV() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  const double ratio = static_cast<double>(this->height) / static_cast<double>(this->width);
  return ignition::math::Angle(2.0 * std::atan(std::tan(this->hfov / 2.0) * ratio));
}

void Camera::SetHFOV(const ignition::math::Angle &_angle)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->hfov = _angle.Radian();
}

ignition::math::Pose3d Camera::WorldPose() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->pose;
}

double Camera::RenderRate() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->renderRate;
}

void Camera::SetRenderRate(const double _hz)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->renderRate = _hz > 0.0 && std::isfinite(_hz) ? _hz : 0.0;
}

event::ConnectionPtr Camera::ConnectNewImageFrame(NewFrameCallback _subscriber)
{
  return this->newImageFrame.Connect(_subscriber);
}

void Camera::Frame(const ignition::math::Pose3d &_worldPose, std::vector<unsigned char> _frame)
{
  const unsigned char *bytes;
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    this->pose = _worldPose;
    this->data = std::move(_frame);
    bytes = this->data.data();
  }
  // the buffer stays until the next frame, which this thread makes (the physics thread)
  this->newImageFrame(bytes, this->width, this->height, this->ImageDepth(), this->format);
}
}  // namespace rendering
}  // namespace gazebo

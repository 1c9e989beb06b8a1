// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the rendering pointer types plugins name (std::shared_ptr,
// as Gazebo 11's). racebot's rendering API is a camera's image and geometry (rendering/Camera.hh), not OGRE's scene.
#ifndef GAZEBO_RENDERING_RENDERTYPES_HH_
#define GAZEBO_RENDERING_RENDERTYPES_HH_

#include <memory>

namespace gazebo
{
namespace rendering
{
class Visual;
class Camera;
class Distortion;
typedef std::shared_ptr<Visual> VisualPtr;
typedef std::shared_ptr<Camera> CameraPtr;
typedef std::shared_ptr<Distortion> DistortionPtr;
}  // namespace rendering
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the visual pointer type VisualPlugin names.
// racebot has no rendering API for plugins (docs/SUPPORTED.md).
#ifndef GAZEBO_RENDERING_RENDERTYPES_HH_
#define GAZEBO_RENDERING_RENDERTYPES_HH_

#include <memory>

namespace gazebo
{
namespace rendering
{
class Visual;
typedef std::shared_ptr<Visual> VisualPtr;
}  // namespace rendering
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::PhysicsEngine, the step settings plugins
// read (World::Physics()). GetGravity is Gazebo 7's (World::Gravity() since Gazebo 8), kept for plugins that call it.
#ifndef GAZEBO_PHYSICS_PHYSICSENGINE_HH_
#define GAZEBO_PHYSICS_PHYSICSENGINE_HH_

#include <ignition/math/Vector3.hh>

#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE PhysicsEngine
{
public:
  double GetMaxStepSize() const;
  double GetRealTimeUpdateRate() const;
  ignition::math::Vector3d GetGravity() const;
};
}  // namespace physics
}  // namespace gazebo

#endif

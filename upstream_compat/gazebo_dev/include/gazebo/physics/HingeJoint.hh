// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::HingeJoint, the one-axis joint template
// Gazebo's engines derive their hinges from, which gazebo_plugins' laser and range plugins include without using.
// A plugin reads a hinge through physics::Joint (Joint.hh).
#ifndef GAZEBO_PHYSICS_HINGEJOINT_HH_
#define GAZEBO_PHYSICS_HINGEJOINT_HH_

#include "gazebo/physics/Joint.hh"

namespace gazebo
{
namespace physics
{
template<class T>
class HingeJoint : public T
{
public:
  using T::T;
};
}  // namespace physics
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::JointWrench, the forces and torques through
// a joint (Joint::GetForceTorque: racebot measures body2, what the parent applies to the child link, in the child
// link's frame, the torque about its origin; body1 is its opposite) or at a contact point (physics::Contact).
#ifndef GAZEBO_PHYSICS_JOINTWRENCH_HH_
#define GAZEBO_PHYSICS_JOINTWRENCH_HH_

#include <ignition/math/Vector3.hh>

namespace gazebo
{
namespace physics
{
class JointWrench
{
public:
  ignition::math::Vector3d body1Force;
  ignition::math::Vector3d body2Force;
  ignition::math::Vector3d body1Torque;
  ignition::math::Vector3d body2Torque;
};
}  // namespace physics
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::Inertial, a link's mass properties as
// Link::GetInertial() gives them. Read-only: racebot's engine holds the link's mass (Gazebo 11's setters with
// Link::UpdateMass are not offered). The moments are in the inertial frame (Pose()), principal ones: PyBullet
// diagonalizes a URDF/SDF inertia tensor when it loads the body, so the products are 0 in that frame.
#ifndef GAZEBO_PHYSICS_INERTIAL_HH_
#define GAZEBO_PHYSICS_INERTIAL_HH_

#include <ignition/math/Matrix3.hh>
#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE Inertial
{
public:
  Inertial() = default;
  Inertial(double _mass, const ignition::math::Pose3d &_pose, const ignition::math::Vector3d &_principal)
    : mass(_mass), cog(_pose), principals(_principal) {}

  double Mass() const { return this->mass; }
  // the centre of gravity in the link frame, and the inertial frame (its rotation gives the moments' axes)
  const ignition::math::Vector3d &CoG() const { return this->cog.Pos(); }
  ignition::math::Pose3d Pose() const { return this->cog; }
  ignition::math::Vector3d PrincipalMoments() const { return this->principals; }
  ignition::math::Vector3d ProductsOfInertia() const { return this->products; }
  double IXX() const { return this->principals.X(); }
  double IYY() const { return this->principals.Y(); }
  double IZZ() const { return this->principals.Z(); }
  double IXY() const { return this->products.X(); }
  double IXZ() const { return this->products.Y(); }
  double IYZ() const { return this->products.Z(); }
  // the moments in the inertial frame, as Gazebo 11's MOI()
  ignition::math::Matrix3d MOI() const
  {
    return ignition::math::Matrix3d(this->IXX(), this->IXY(), this->IXZ(), this->IXY(), this->IYY(), this->IYZ(),
                                    this->IXZ(), this->IYZ(), this->IZZ());
  }

private:
  double mass = 1.0;  // Gazebo's defaults: 1 kg, unit moments at the link origin
  ignition::math::Pose3d cog;
  ignition::math::Vector3d principals{1.0, 1.0, 1.0};
  ignition::math::Vector3d products{0.0, 0.0, 0.0};
};
}  // namespace physics
}  // namespace gazebo

#endif

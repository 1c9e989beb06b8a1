// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::Link, a link's pose, velocity and the
// forces a plugin applies to it (world frame unless the name says Relative; they act for the coming step).
#ifndef GAZEBO_PHYSICS_LINK_HH_
#define GAZEBO_PHYSICS_LINK_HH_

#include <string>

#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/physics/Inertial.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE Link
{
public:
  Link(const ModelPtr &_model, const std::string &_name, int _handle);
  std::string GetName() const { return this->name; }
  std::string GetScopedName(bool _prependWorldName = false) const;
  ModelPtr GetModel() const { return this->model.lock(); }
  ModelPtr GetParentModel() const { return this->model.lock(); }
  WorldPtr GetWorld() const;

  const ignition::math::Pose3d &WorldPose() const;
  ignition::math::Pose3d WorldCoGPose() const;
  // in its model's frame (Entity::RelativePose: a link's parent is its model)
  ignition::math::Pose3d RelativePose() const;
  ignition::math::Vector3d WorldLinearVel() const;
  // of the point at `_offset` from the link frame's origin, in the link frame; with `_q`, the offset's frame is
  // `_q` in the world
  ignition::math::Vector3d WorldLinearVel(const ignition::math::Vector3d &_offset) const;
  ignition::math::Vector3d WorldLinearVel(const ignition::math::Vector3d &_offset,
                                          const ignition::math::Quaterniond &_q) const;
  ignition::math::Vector3d WorldCoGLinearVel() const;
  ignition::math::Vector3d WorldAngularVel() const;
  ignition::math::Vector3d RelativeLinearVel() const;
  ignition::math::Vector3d RelativeAngularVel() const;

  void AddForce(const ignition::math::Vector3d &_force);
  void AddRelativeForce(const ignition::math::Vector3d &_force);
  void AddTorque(const ignition::math::Vector3d &_torque);
  void AddRelativeTorque(const ignition::math::Vector3d &_torque);
  // a force at a point given in the world frame: the force at the CoG plus its moment about the CoG
  void AddForceAtWorldPosition(const ignition::math::Vector3d &_force, const ignition::math::Vector3d &_pos);

  // the force and torque applied to the link for the coming step (AddForce & co.), world axes, the torque about
  // the CoG; RelativeForce / RelativeTorque: in the link frame
  ignition::math::Vector3d WorldForce() const;
  ignition::math::Vector3d WorldTorque() const;
  ignition::math::Vector3d RelativeForce() const;
  ignition::math::Vector3d RelativeTorque() const;
  // the link's mass properties now (a copy: racebot's engine holds them; Gazebo's object is the link's own)
  InertialPtr GetInertial() const;
  double GetMass() const;  // not Gazebo 11's: GetInertial()->Mass(); kept for plugins written against racebot
  int Handle() const { return this->handle; }

private:
  boost::weak_ptr<Model> model;
  std::string name;
  int handle;
  mutable ignition::math::Pose3d pose;
};
}  // namespace physics
}  // namespace gazebo

#endif

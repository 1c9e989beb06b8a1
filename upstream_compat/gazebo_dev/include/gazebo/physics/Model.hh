// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::Model, a spawned model's links and joints
// by name, its pose and velocity.
#ifndef GAZEBO_PHYSICS_MODEL_HH_
#define GAZEBO_PHYSICS_MODEL_HH_

#include <string>

#include <boost/enable_shared_from_this.hpp>
#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/physics/JointController.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE Model : public boost::enable_shared_from_this<Model>
{
public:
  Model(const WorldPtr &_world, const std::string &_name, int _handle, bool _static);
  std::string GetName() const { return this->name; }
  std::string GetScopedName(bool _prependWorldName = false) const;
  WorldPtr GetWorld() const { return this->world.lock(); }
  bool IsStatic() const { return this->isStatic; }

  // A joint or link by its name or its scoped name ("model::joint"); null when there is none.
  JointPtr GetJoint(const std::string &_name);
  const Joint_V &GetJoints() const { return this->joints; }
  unsigned int GetJointCount() const { return this->joints.size(); }
  // "canonical" (the default): the model's canonical (root) link.
  LinkPtr GetLink(const std::string &_name = "canonical") const;
  LinkPtr GetChildLink(const std::string &_name) const;
  const Link_V &GetLinks() const { return this->links; }
  unsigned int GetChildCount() const { return this->links.size(); }

  const ignition::math::Pose3d &WorldPose() const;
  void SetWorldPose(const ignition::math::Pose3d &_pose, const bool _notify = true, const bool _publish = true);
  ignition::math::Vector3d WorldLinearVel() const;
  ignition::math::Vector3d WorldAngularVel() const;
  ignition::math::Vector3d RelativeLinearVel() const;
  ignition::math::Vector3d RelativeAngularVel() const;
  void SetLinearVel(const ignition::math::Vector3d &_vel);
  void SetAngularVel(const ignition::math::Vector3d &_vel);
  void SetJointPosition(const std::string &_jointName, double _position);
  // its joints' forces and PIDs, applied at every world update after worldUpdateBegin (made at the first call)
  JointControllerPtr GetJointController();

  // racebot's host builds the model: its links (the canonical one first) and joints.
  int Handle() const { return this->handle; }
  void AddLink(const LinkPtr &_link) { this->links.push_back(_link); }
  void AddJoint(const JointPtr &_joint) { this->joints.push_back(_joint); }
  // Gazebo's Model::Update: its JointController's, when it has one
  void Update()
  {
    if (this->jointController)
      this->jointController->Update();
  }
  void ResetJointController()
  {
    if (this->jointController)
      this->jointController->Reset();
  }

private:
  std::string Unscoped(const std::string &_name) const;
  boost::weak_ptr<World> world;
  std::string name;
  int handle;
  bool isStatic;
  Link_V links;
  Joint_V joints;
  JointControllerPtr jointController;
  mutable ignition::math::Pose3d pose;
};
}  // namespace physics
}  // namespace gazebo

#endif

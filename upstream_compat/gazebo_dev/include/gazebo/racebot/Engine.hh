// Not Gazebo's: the seam between racebot's Gazebo 11 plugin API and its simulator. The physics classes
// (World, Model, Link, Joint) keep only names and the engine's handles; every state and command goes through the
// one Engine the plugin host installs (racebot_sim_bridge's gazebo_host module, which calls the Python engine).
// Handles are the host's small integers: a model's, and a link's or joint's within the host's tables.
#ifndef GAZEBO_RACEBOT_ENGINE_HH_
#define GAZEBO_RACEBOT_ENGINE_HH_

#include <string>

#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/util/system.hh"

namespace gazebo
{
namespace racebot
{
class GZ_PHYSICS_VISIBLE Engine
{
public:
  virtual ~Engine() = default;
  virtual double SimTime() = 0;
  virtual double RealTime() = 0;
  virtual double StepSize() = 0;
  virtual ignition::math::Vector3d Gravity() = 0;

  virtual double JointPosition(int _joint) = 0;
  virtual double JointVelocity(int _joint) = 0;
  virtual double JointForce(int _joint) = 0;                  // the effort applied for the coming step
  virtual void JointSetVelocity(int _joint, double _vel) = 0;  // at once, as Gazebo's SetVelocity
  virtual void JointSetForce(int _joint, double _force) = 0;   // adds to the coming step's effort
  virtual void JointSetPosition(int _joint, double _pos) = 0;
  virtual void JointSetMotor(int _joint, double _vel, double _fmax) = 0;  // SetParam("vel"/"fmax")

  virtual ignition::math::Pose3d LinkWorldPose(int _link) = 0;
  virtual ignition::math::Pose3d LinkWorldCoGPose(int _link) = 0;
  virtual ignition::math::Vector3d LinkWorldLinearVel(int _link) = 0;     // of the link frame's origin
  virtual ignition::math::Vector3d LinkWorldCoGLinearVel(int _link) = 0;
  virtual ignition::math::Vector3d LinkWorldAngularVel(int _link) = 0;
  virtual void LinkAddForce(int _link, const ignition::math::Vector3d &_force) = 0;  // world frame, at the CoG
  virtual void LinkAddTorque(int _link, const ignition::math::Vector3d &_torque) = 0;
  virtual double LinkMass(int _link) = 0;
  // mass, the inertial frame in the link frame, the principal moments in it
  virtual void LinkInertial(int _link, double &_mass, ignition::math::Pose3d &_pose,
                            ignition::math::Vector3d &_principal) = 0;
  // the force and torque (about the CoG) applied to the link for the coming step, world axes (Link::WorldForce)
  virtual ignition::math::Vector3d LinkWorldForce(int _link) = 0;
  virtual ignition::math::Vector3d LinkWorldTorque(int _link) = 0;
  // what the joint's parent applies to its child link through it in the last step, in the child link's frame, the
  // torque about the link's origin (JointWrench::body2Force / body2Torque)
  virtual void JointWrench(int _joint, ignition::math::Vector3d &_force, ignition::math::Vector3d &_torque) = 0;

  virtual void ModelSetWorldPose(int _model, const ignition::math::Pose3d &_pose) = 0;  // of the model frame
  virtual void ModelSetLinearVel(int _model, const ignition::math::Vector3d &_vel) = 0;
  virtual void ModelSetAngularVel(int _model, const ignition::math::Vector3d &_vel) = 0;
  virtual ignition::math::Pose3d ModelWorldPose(int _model) = 0;
};

// The engine the physics classes call; the host sets it before it loads a plugin. Calling a physics method with
// none set throws std::logic_error.
GZ_PHYSICS_VISIBLE void SetEngine(Engine *_engine);
GZ_PHYSICS_VISIBLE Engine &TheEngine();
}  // namespace racebot
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::JointController, Model::GetJointController():
// forces, and position and velocity PIDs (common::PID) toward targets, applied as joint efforts at every world update
// after worldUpdateBegin (Gazebo's Model::Update). Joints are keyed by their scoped names (model::joint), as Gazebo's.
#ifndef GAZEBO_PHYSICS_JOINTCONTROLLER_HH_
#define GAZEBO_PHYSICS_JOINTCONTROLLER_HH_

#include <map>
#include <string>

#include "gazebo/common/PID.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE JointController
{
public:
  explicit JointController(ModelPtr _model);
  void AddJoint(JointPtr _joint);
  void Reset();
  void Update();
  void SetForce(const std::string &_jointName, double _force) { this->forces[_jointName] = _force; }
  bool SetPositionPID(const std::string &_jointName, const common::PID &_pid);
  bool SetPositionTarget(const std::string &_jointName, double _target);
  bool SetVelocityPID(const std::string &_jointName, const common::PID &_pid);
  bool SetVelocityTarget(const std::string &_jointName, double _target);
  bool SetJointPosition(const std::string &_name, double _position, int _index = 0);
  std::map<std::string, JointPtr> GetJoints() const { return this->joints; }
  std::map<std::string, common::PID> GetPositionPIDs() const { return this->posPids; }
  std::map<std::string, common::PID> GetVelocityPIDs() const { return this->velPids; }
  std::map<std::string, double> GetForces() const { return this->forces; }
  std::map<std::string, double> GetPositions() const { return this->positions; }
  std::map<std::string, double> GetVelocities() const { return this->velocities; }
  common::Time GetLastUpdateTime() const { return this->prevUpdateTime; }

private:
  boost::weak_ptr<Model> model;
  std::map<std::string, JointPtr> joints;
  std::map<std::string, common::PID> posPids;
  std::map<std::string, common::PID> velPids;
  std::map<std::string, double> forces;
  std::map<std::string, double> positions;
  std::map<std::string, double> velocities;
  common::Time prevUpdateTime;
};
typedef boost::shared_ptr<JointController> JointControllerPtr;
}  // namespace physics
}  // namespace gazebo

#endif

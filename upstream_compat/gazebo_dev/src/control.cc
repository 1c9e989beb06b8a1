// racebot's Gazebo 11 plugin API: common::PID and physics::JointController, as Gazebo 11's.
#include <cmath>

#include "gazebo/common/PID.hh"
#include "gazebo/physics/Joint.hh"
#include "gazebo/physics/JointController.hh"
#include "gazebo/physics/Model.hh"
#include "gazebo/physics/World.hh"

namespace gazebo
{
namespace common
{
PID::PID(double _p, double _i, double _d, double _imax, double _imin, double _cmdMax, double _cmdMin)
{
  this->Init(_p, _i, _d, _imax, _imin, _cmdMax, _cmdMin);
}

void PID::Init(double _p, double _i, double _d, double _imax, double _imin, double _cmdMax, double _cmdMin)
{
  this->pGain = _p;
  this->iGain = _i;
  this->dGain = _d;
  this->iMax = _imax;
  this->iMin = _imin;
  this->cmdMax = _cmdMax;
  this->cmdMin = _cmdMin;
  this->Reset();
}

void PID::Reset()
{
  this->pErrLast = this->pErr = this->iErr = this->dErr = this->cmd = 0.0;
}

double PID::Update(double _error, common::Time _dt)
{
  this->pErr = _error;
  if (_dt == common::Time(0, 0) || std::isnan(_error) || std::isinf(_error))
    return 0.0;
  const double pTerm = this->pGain * this->pErr;
  this->iErr = this->iErr + _dt.Double() * this->pErr;
  double iTerm = this->iGain * this->iErr;
  // the i-term held at its bound, and the error with it (as upstream: iErr = iTerm / iGain)
  if (iTerm > this->iMax)
  {
    iTerm = this->iMax;
    this->iErr = iTerm / this->iGain;
  }
  else if (iTerm < this->iMin)
  {
    iTerm = this->iMin;
    this->iErr = iTerm / this->iGain;
  }
  this->dErr = (this->pErr - this->pErrLast) / _dt.Double();
  this->pErrLast = this->pErr;
  const double dTerm = this->dGain * this->dErr;
  this->cmd = -pTerm - iTerm - dTerm;
  if (this->cmdMax >= this->cmdMin)
    this->cmd = std::min(std::max(this->cmd, this->cmdMin), this->cmdMax);
  return this->cmd;
}
}  // namespace common

namespace physics
{
JointController::JointController(ModelPtr _model) : model(_model) {}

void JointController::AddJoint(JointPtr _joint) { this->joints[_joint->GetScopedName()] = _joint; }

void JointController::Reset()
{
  this->forces.clear();
  this->positions.clear();
  this->velocities.clear();
  for (auto &pid : this->posPids)
    pid.second.Reset();
  for (auto &pid : this->velPids)
    pid.second.Reset();
  this->prevUpdateTime = common::Time();
}

void JointController::Update()
{
  ModelPtr owner = this->model.lock();
  if (!owner)
    return;
  const common::Time now = owner->GetWorld()->SimTime();
  const common::Time step = now - this->prevUpdateTime;
  this->prevUpdateTime = now;
  if (step <= common::Time(0, 0))
    return;
  for (const auto &force : this->forces)
  {
    auto joint = this->joints.find(force.first);
    if (joint != this->joints.end())
      joint->second->SetForce(0, force.second);
  }
  for (auto &pid : this->posPids)
  {
    auto target = this->positions.find(pid.first);
    auto joint = this->joints.find(pid.first);
    if (target != this->positions.end() && joint != this->joints.end())
      joint->second->SetForce(0, pid.second.Update(joint->second->Position(0) - target->second, step));
  }
  for (auto &pid : this->velPids)
  {
    auto target = this->velocities.find(pid.first);
    auto joint = this->joints.find(pid.first);
    if (target != this->velocities.end() && joint != this->joints.end())
      joint->second->SetForce(0, pid.second.Update(joint->second->GetVelocity(0) - target->second, step));
  }
}

bool JointController::SetPositionPID(const std::string &_jointName, const common::PID &_pid)
{
  if (this->joints.count(_jointName) == 0)
    return false;
  this->posPids[_jointName] = _pid;
  return true;
}

bool JointController::SetPositionTarget(const std::string &_jointName, double _target)
{
  if (this->posPids.count(_jointName) == 0)
    return false;
  this->positions[_jointName] = _target;
  return true;
}

bool JointController::SetVelocityPID(const std::string &_jointName, const common::PID &_pid)
{
  if (this->joints.count(_jointName) == 0)
    return false;
  this->velPids[_jointName] = _pid;
  return true;
}

bool JointController::SetVelocityTarget(const std::string &_jointName, double _target)
{
  if (this->velPids.count(_jointName) == 0)
    return false;
  this->velocities[_jointName] = _target;
  return true;
}

bool JointController::SetJointPosition(const std::string &_name, double _position, int _index)
{
  auto joint = this->joints.find(_name);
  if (joint == this->joints.end())
    return false;
  return joint->second->SetPosition(_index, _position);
}
}  // namespace physics
}  // namespace gazebo

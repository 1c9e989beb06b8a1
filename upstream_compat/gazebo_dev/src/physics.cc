// racebot's Gazebo 11 plugin API: the physics classes, each call passed to the Engine the plugin host installs.
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "gazebo/common/Console.hh"
#include "gazebo/physics/Contact.hh"
#include "gazebo/physics/Joint.hh"
#include "gazebo/physics/Link.hh"
#include "gazebo/physics/Model.hh"
#include "gazebo/physics/World.hh"
#include "gazebo/racebot/Engine.hh"

namespace gazebo
{
namespace racebot
{
namespace
{
Engine *engine = nullptr;
}

void SetEngine(Engine *_engine) { engine = _engine; }

Engine &TheEngine()
{
  if (engine == nullptr)
    throw std::logic_error("racebot: a Gazebo physics method was called outside racebot's world server "
                           "(no engine behind gazebo::physics)");
  return *engine;
}
}  // namespace racebot

namespace physics
{
using ignition::math::Pose3d;
using ignition::math::Vector3d;
using racebot::TheEngine;

namespace
{
WorldPtr theWorld;

std::string Scoped(const WorldPtr &_world, bool _prependWorldName, const std::string &_name)
{
  if (_prependWorldName && _world)
    return _world->Name() + "::" + _name;
  return _name;
}
}  // namespace

// -- World, PhysicsEngine ----------------------------------------------------------------------------------------
double PhysicsEngine::GetMaxStepSize() const { return TheEngine().StepSize(); }
double PhysicsEngine::GetRealTimeUpdateRate() const { return 1.0 / TheEngine().StepSize(); }
Vector3d PhysicsEngine::GetGravity() const { return TheEngine().Gravity(); }

World::World(const std::string &_name) : name(_name), physics(new PhysicsEngine()) {}
std::string World::Name() const { return this->name; }
common::Time World::SimTime() const { return common::Time(TheEngine().SimTime()); }
common::Time World::RealTime() const { return common::Time(TheEngine().RealTime()); }
PhysicsEnginePtr World::Physics() const { return this->physics; }
Vector3d World::Gravity() const { return TheEngine().Gravity(); }

ModelPtr World::ModelByName(const std::string &_name) const
{
  auto found = this->models.find(_name);
  return found == this->models.end() ? ModelPtr() : found->second;
}

Model_V World::Models() const
{
  Model_V result;
  for (const auto &entry : this->models)
    result.push_back(entry.second);
  return result;
}

unsigned int World::ModelCount() const { return this->models.size(); }
uint64_t World::Iterations() const { return this->iterations; }
void World::AddModel(const ModelPtr &_model) { this->models[_model->GetName()] = _model; }
void World::RemoveModel(const std::string &_name) { this->models.erase(_name); }
void World::SetIterations(uint64_t _iterations) { this->iterations = _iterations; }

WorldPtr get_world(const std::string &_name)
{
  if (!theWorld || (!_name.empty() && _name != theWorld->Name()))
    throw std::runtime_error("Unable to find world by name in physics::get_world(" + _name + ")");
  return theWorld;
}

void set_world(const WorldPtr &_world) { theWorld = _world; }

// -- Model ------------------------------------------------------------------------------------------------------
Model::Model(const WorldPtr &_world, const std::string &_name, int _handle, bool _static)
  : world(_world), name(_name), handle(_handle), isStatic(_static) {}

std::string Model::GetScopedName(bool _prependWorldName) const
{
  return Scoped(this->GetWorld(), _prependWorldName, this->name);
}

std::string Model::Unscoped(const std::string &_name) const
{
  const std::string prefix = this->name + "::";
  return _name.compare(0, prefix.size(), prefix) == 0 ? _name.substr(prefix.size()) : _name;
}

JointPtr Model::GetJoint(const std::string &_name)
{
  const std::string wanted = this->Unscoped(_name);
  for (const auto &joint : this->joints)
    if (joint->GetName() == wanted)
      return joint;
  return JointPtr();
}

LinkPtr Model::GetLink(const std::string &_name) const
{
  if (_name == "canonical")
    return this->links.empty() ? LinkPtr() : this->links.front();
  return this->GetChildLink(_name);
}

LinkPtr Model::GetChildLink(const std::string &_name) const
{
  const std::string wanted = this->Unscoped(_name);
  for (const auto &link : this->links)
    if (link->GetName() == wanted)
      return link;
  return LinkPtr();
}

const Pose3d &Model::WorldPose() const
{
  this->pose = TheEngine().ModelWorldPose(this->handle);
  return this->pose;
}

void Model::SetWorldPose(const Pose3d &_pose, const bool, const bool)
{
  TheEngine().ModelSetWorldPose(this->handle, _pose);
}

Vector3d Model::WorldLinearVel() const
{
  LinkPtr canonical = this->GetLink();
  return canonical ? canonical->WorldLinearVel() : Vector3d::Zero;
}

Vector3d Model::WorldAngularVel() const
{
  LinkPtr canonical = this->GetLink();
  return canonical ? canonical->WorldAngularVel() : Vector3d::Zero;
}

Vector3d Model::RelativeLinearVel() const { return this->WorldPose().Rot().RotateVectorReverse(this->WorldLinearVel()); }
Vector3d Model::RelativeAngularVel() const
{
  return this->WorldPose().Rot().RotateVectorReverse(this->WorldAngularVel());
}
void Model::SetLinearVel(const Vector3d &_vel) { TheEngine().ModelSetLinearVel(this->handle, _vel); }
void Model::SetAngularVel(const Vector3d &_vel) { TheEngine().ModelSetAngularVel(this->handle, _vel); }

JointControllerPtr Model::GetJointController()
{
  if (!this->jointController)
  {
    this->jointController.reset(new JointController(this->shared_from_this()));
    for (const auto &joint : this->joints)
      this->jointController->AddJoint(joint);
  }
  return this->jointController;
}

void Model::SetJointPosition(const std::string &_jointName, double _position)
{
  JointPtr joint = this->GetJoint(_jointName);
  if (joint)
    joint->SetPosition(0, _position);
  else
    gzerr << "Model[" << this->name << "] has no joint named [" << _jointName << "]\n";
}

// -- Link -------------------------------------------------------------------------------------------------------
Link::Link(const ModelPtr &_model, const std::string &_name, int _handle)
  : model(_model), name(_name), handle(_handle) {}

std::string Link::GetScopedName(bool _prependWorldName) const
{
  ModelPtr owner = this->GetModel();
  const std::string scoped = owner ? owner->GetName() + "::" + this->name : this->name;
  return Scoped(this->GetWorld(), _prependWorldName, scoped);
}

WorldPtr Link::GetWorld() const
{
  ModelPtr owner = this->GetModel();
  return owner ? owner->GetWorld() : WorldPtr();
}

const Pose3d &Link::WorldPose() const
{
  this->pose = TheEngine().LinkWorldPose(this->handle);
  return this->pose;
}

Pose3d Link::RelativePose() const
{
  ModelPtr parent = this->model.lock();
  if (!parent)
    return this->WorldPose();
  return this->WorldPose() - parent->WorldPose();
}

Pose3d Link::WorldCoGPose() const { return TheEngine().LinkWorldCoGPose(this->handle); }
Vector3d Link::WorldLinearVel() const { return TheEngine().LinkWorldLinearVel(this->handle); }
Vector3d Link::WorldLinearVel(const Vector3d &_offset) const
{
  return this->WorldLinearVel(_offset, this->WorldPose().Rot());
}
Vector3d Link::WorldLinearVel(const Vector3d &_offset, const ignition::math::Quaterniond &_q) const
{
  return this->WorldLinearVel() + this->WorldAngularVel().Cross(_q.RotateVector(_offset));
}
Vector3d Link::WorldCoGLinearVel() const { return TheEngine().LinkWorldCoGLinearVel(this->handle); }
Vector3d Link::WorldAngularVel() const { return TheEngine().LinkWorldAngularVel(this->handle); }
Vector3d Link::RelativeLinearVel() const { return this->WorldPose().Rot().RotateVectorReverse(this->WorldLinearVel()); }
Vector3d Link::RelativeAngularVel() const
{
  return this->WorldPose().Rot().RotateVectorReverse(this->WorldAngularVel());
}

void Link::AddForce(const Vector3d &_force) { TheEngine().LinkAddForce(this->handle, _force); }
void Link::AddTorque(const Vector3d &_torque) { TheEngine().LinkAddTorque(this->handle, _torque); }

// ODE's dBodyAddRelForce / dBodyAddRelTorque: in the body's frame, which is the link's inertial (CoG) frame
void Link::AddRelativeForce(const Vector3d &_force)
{
  this->AddForce(this->WorldCoGPose().Rot().RotateVector(_force));
}

void Link::AddRelativeTorque(const Vector3d &_torque)
{
  this->AddTorque(this->WorldCoGPose().Rot().RotateVector(_torque));
}

void Link::AddForceAtWorldPosition(const Vector3d &_force, const Vector3d &_pos)
{
  const Vector3d arm = _pos - this->WorldCoGPose().Pos();
  this->AddForce(_force);
  this->AddTorque(arm.Cross(_force));
}

double Link::GetMass() const { return TheEngine().LinkMass(this->handle); }
InertialPtr Link::GetInertial() const
{
  double mass = 0.0;
  Pose3d pose;
  Vector3d principal;
  TheEngine().LinkInertial(this->handle, mass, pose, principal);
  return boost::make_shared<Inertial>(mass, pose, principal);
}
Vector3d Link::WorldForce() const { return TheEngine().LinkWorldForce(this->handle); }
Vector3d Link::WorldTorque() const { return TheEngine().LinkWorldTorque(this->handle); }
Vector3d Link::RelativeForce() const { return this->WorldPose().Rot().RotateVectorReverse(this->WorldForce()); }
Vector3d Link::RelativeTorque() const { return this->WorldPose().Rot().RotateVectorReverse(this->WorldTorque()); }

// -- Joint ------------------------------------------------------------------------------------------------------
Joint::Joint(const ModelPtr &_model, const std::string &_name, int _handle, const LinkPtr &_parent,
             const LinkPtr &_child, const JointLimits &_limits)
  : model(_model), name(_name), handle(_handle), parent(_parent), child(_child), limits(_limits) {}

std::string Joint::GetScopedName(bool _prependWorldName) const
{
  ModelPtr owner = this->GetModel();
  const std::string scoped = owner ? owner->GetName() + "::" + this->name : this->name;
  return Scoped(owner ? owner->GetWorld() : WorldPtr(), _prependWorldName, scoped);
}

bool Joint::ValidIndex(unsigned int _index, const char *_method) const
{
  if (_index == 0)
    return true;
  gzerr << "Calling Joint::" << _method << " with an index [" << _index << "] out of range (joint [" << this->name
        << "] has one axis)\n";
  return false;
}

double Joint::Position(const unsigned int _index) const
{
  if (!this->ValidIndex(_index, "Position"))
    return ignition::math::NAN_D;  // Gazebo's Joint::Position for a bad index
  return TheEngine().JointPosition(this->handle);
}

double Joint::GetVelocity(unsigned int _index) const
{
  if (!this->ValidIndex(_index, "GetVelocity"))
    return 0.0;
  return TheEngine().JointVelocity(this->handle);
}

double Joint::GetForce(unsigned int _index)
{
  if (!this->ValidIndex(_index, "GetForce"))
    return 0.0;
  return TheEngine().JointForce(this->handle);
}

void Joint::SetVelocity(unsigned int _index, double _vel)
{
  if (!this->ValidIndex(_index, "SetVelocity"))
    return;
  TheEngine().JointSetVelocity(this->handle, _vel);
}

void Joint::SetForce(unsigned int _index, double _effort)
{
  if (!this->ValidIndex(_index, "SetForce"))
    return;
  // Joint::CheckAndTruncateForce: none in the direction of the velocity once beyond the velocity limit, and
  // within the effort limit, each where there is one (>= 0)
  if (this->limits.velocity >= 0.0)
  {
    const double velocity = TheEngine().JointVelocity(this->handle);
    if (velocity > this->limits.velocity)
      _effort = _effort > 0 ? 0 : _effort;
    else if (velocity < -this->limits.velocity)
      _effort = _effort < 0 ? 0 : _effort;
  }
  if (this->limits.effort >= 0.0)
    _effort = ignition::math::clamp(_effort, -this->limits.effort, this->limits.effort);
  TheEngine().JointSetForce(this->handle, _effort);
}

bool Joint::SetPosition(const unsigned int _index, const double _position, const bool)
{
  if (!this->ValidIndex(_index, "SetPosition"))
    return false;
  TheEngine().JointSetPosition(this->handle, _position);
  return true;
}

JointWrench Joint::GetForceTorque(unsigned int _index)
{
  JointWrench wrench;
  if (!this->ValidIndex(_index, "GetForceTorque"))
    return wrench;
  TheEngine().JointWrench(this->handle, wrench.body2Force, wrench.body2Torque);
  wrench.body1Force = -wrench.body2Force;
  wrench.body1Torque = -wrench.body2Torque;
  return wrench;
}

double Joint::LowerLimit(unsigned int _index) const
{
  if (!this->ValidIndex(_index, "LowerLimit"))
    return 0.0;
  return this->limits.lower;
}

double Joint::UpperLimit(unsigned int _index) const
{
  if (!this->ValidIndex(_index, "UpperLimit"))
    return 0.0;
  return this->limits.upper;
}

double Joint::GetEffortLimit(unsigned int _index)
{
  if (!this->ValidIndex(_index, "GetEffortLimit"))
    return -1.0;
  return this->limits.effort;
}

double Joint::GetVelocityLimit(unsigned int _index)
{
  if (!this->ValidIndex(_index, "GetVelocityLimit"))
    return -1.0;
  return this->limits.velocity;
}

void Joint::SetEffortLimit(unsigned int _index, double _effort)
{
  if (!this->ValidIndex(_index, "SetEffortLimit"))
    return;
  this->limits.effort = _effort;
}

void Joint::SetVelocityLimit(unsigned int _index, double _velocity)
{
  if (!this->ValidIndex(_index, "SetVelocityLimit"))
    return;
  this->limits.velocity = _velocity;
}

namespace
{
bool AsDouble(const boost::any &_value, double &_out)
{
  try
  {
    if (_value.type() == typeid(double))
      _out = boost::any_cast<double>(_value);
    else if (_value.type() == typeid(float))
      _out = boost::any_cast<float>(_value);
    else if (_value.type() == typeid(int))
      _out = boost::any_cast<int>(_value);
    else if (_value.type() == typeid(unsigned int))
      _out = boost::any_cast<unsigned int>(_value);
    else
      return false;
  }
  catch (const boost::bad_any_cast &)
  {
    return false;
  }
  return true;
}
}  // namespace

bool Joint::SetParam(const std::string &_key, unsigned int _index, const boost::any &_value)
{
  if (!this->ValidIndex(_index, "SetParam"))
    return false;
  double value = 0.0;
  if (_key != "fmax" && _key != "vel")
  {
    gzerr << "Unable to handle joint attribute[" << _key << "] (racebot has the joint motor's fmax and vel)\n";
    return false;
  }
  if (!AsDouble(_value, value))
  {
    gzerr << "Joint::SetParam(" << _key << "): the value must be a number (double, float, int)\n";
    return false;
  }
  (_key == "fmax" ? this->motorFmax : this->motorVel) = value;
  TheEngine().JointSetMotor(this->handle, this->motorVel, this->motorFmax);
  return true;
}

double Joint::GetParam(const std::string &_key, unsigned int _index)
{
  if (!this->ValidIndex(_index, "GetParam"))
    return 0.0;
  if (_key == "fmax")
    return this->motorFmax;
  if (_key == "vel")
    return this->motorVel;
  gzerr << "Unable to get joint attribute[" << _key << "] (racebot has the joint motor's fmax and vel)\n";
  return 0.0;
}

// -- Contact ----------------------------------------------------------------------------------------------------
Contact::Contact() { this->Reset(); }

Contact &Contact::operator=(const msgs::Contact &_contact)
{
  this->Reset();
  try
  {
    this->world = get_world(_contact.world());
  }
  catch (const std::exception &)
  {
    this->world.reset();
  }
  this->count = std::min(_contact.position_size(), MAX_CONTACT_JOINTS);
  for (int j = 0; j < this->count; ++j)
  {
    this->positions[j] = msgs::ConvertIgn(_contact.position(j));
    this->normals[j] = j < _contact.normal_size() ? msgs::ConvertIgn(_contact.normal(j)) : Vector3d::Zero;
    this->depths[j] = j < _contact.depth_size() ? _contact.depth(j) : 0.0;
    if (j < _contact.wrench_size())
    {
      const msgs::JointWrench &w = _contact.wrench(j);
      this->wrench[j].body1Force = msgs::ConvertIgn(w.body_1_wrench().force());
      this->wrench[j].body1Torque = msgs::ConvertIgn(w.body_1_wrench().torque());
      this->wrench[j].body2Force = msgs::ConvertIgn(w.body_2_wrench().force());
      this->wrench[j].body2Torque = msgs::ConvertIgn(w.body_2_wrench().torque());
    }
  }
  this->time = msgs::Convert(_contact.time());
  return *this;
}

void Contact::FillMsg(msgs::Contact &_msg) const
{
  _msg.set_world(this->world ? this->world->Name() : "");
  _msg.clear_position();
  _msg.clear_normal();
  _msg.clear_depth();
  _msg.clear_wrench();
  for (int j = 0; j < this->count; ++j)
  {
    msgs::Set(_msg.add_position(), this->positions[j]);
    msgs::Set(_msg.add_normal(), this->normals[j]);
    _msg.add_depth(this->depths[j]);
    msgs::JointWrench *w = _msg.add_wrench();
    msgs::Set(w->mutable_body_1_wrench()->mutable_force(), this->wrench[j].body1Force);
    msgs::Set(w->mutable_body_1_wrench()->mutable_torque(), this->wrench[j].body1Torque);
    msgs::Set(w->mutable_body_2_wrench()->mutable_force(), this->wrench[j].body2Force);
    msgs::Set(w->mutable_body_2_wrench()->mutable_torque(), this->wrench[j].body2Torque);
  }
  msgs::Set(_msg.mutable_time(), this->time);
}

std::string Contact::DebugString() const
{
  std::ostringstream stream;
  stream << "Depths:\n";
  for (int i = 0; i < this->count; ++i)
    stream << "\t[" << i << "] " << this->depths[i] << "\n";
  stream << "\nPositions:\n";
  for (int i = 0; i < this->count; ++i)
    stream << "\t[" << i << "] " << this->positions[i] << "\n";
  stream << "\nNormals:\n";
  for (int i = 0; i < this->count; ++i)
    stream << "\t[" << i << "] " << this->normals[i] << "\n";
  stream << "\nTime[" << this->time << "]\n";
  return stream.str();
}

void Contact::Reset()
{
  this->count = 0;
  this->collision1 = nullptr;
  this->collision2 = nullptr;
  for (int j = 0; j < MAX_CONTACT_JOINTS; ++j)
  {
    this->wrench[j] = JointWrench();
    this->positions[j] = Vector3d::Zero;
    this->normals[j] = Vector3d::Zero;
    this->depths[j] = 0.0;
  }
  this->time = common::Time();
}
}  // namespace physics
}  // namespace gazebo

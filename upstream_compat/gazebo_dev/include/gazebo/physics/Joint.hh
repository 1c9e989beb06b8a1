// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::Joint, one movable joint (racebot's
// joints have one axis: revolute, continuous or prismatic; `_index` 0; another index gets Gazebo's gzerr and
// nothing is done).
#ifndef GAZEBO_PHYSICS_JOINT_HH_
#define GAZEBO_PHYSICS_JOINT_HH_

#include <string>

#include <boost/any.hpp>
#include <ignition/math/Vector3.hh>

#include "gazebo/physics/JointWrench.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
struct JointLimits
{
  double lower = 0.0;
  double upper = 0.0;
  double effort = -1.0;    // Gazebo's -1: no limit
  double velocity = -1.0;
};

class GZ_PHYSICS_VISIBLE Joint
{
public:
  Joint(const ModelPtr &_model, const std::string &_name, int _handle, const LinkPtr &_parent,
        const LinkPtr &_child, const JointLimits &_limits);
  std::string GetName() const { return this->name; }
  std::string GetScopedName(bool _prependWorldName = false) const;
  ModelPtr GetModel() const { return this->model.lock(); }
  LinkPtr GetParent() const { return this->parent; }
  LinkPtr GetChild() const { return this->child; }
  unsigned int DOF() const { return 1; }
  unsigned int GetAngleCount() const { return 1; }

  double Position(const unsigned int _index = 0) const;
  double GetVelocity(unsigned int _index) const;
  double GetForce(unsigned int _index);
  void SetVelocity(unsigned int _index, double _vel);
  void SetForce(unsigned int _index, double _effort);
  bool SetPosition(const unsigned int _index, const double _position, const bool _preserveWorldVelocity = false);

  // the wrench through the joint in the last step (body2: on the child link; measured from the first call on, so
  // the first reads zero, as a joint whose feedback Gazebo had not been asked for)
  JointWrench GetForceTorque(unsigned int _index);
  double LowerLimit(unsigned int _index = 0) const;
  double UpperLimit(unsigned int _index = 0) const;
  double GetEffortLimit(unsigned int _index);
  double GetVelocityLimit(unsigned int _index);
  void SetEffortLimit(unsigned int _index, double _effort);
  void SetVelocityLimit(unsigned int _index, double _velocity);

  // ODE's joint motor: "fmax" (the most force it may use) and "vel" (its target velocity); other keys are
  // refused with an error, returning false.
  bool SetParam(const std::string &_key, unsigned int _index, const boost::any &_value);
  double GetParam(const std::string &_key, unsigned int _index);

  int Handle() const { return this->handle; }

private:
  bool ValidIndex(unsigned int _index, const char *_method) const;  // gzerr when not, as Gazebo
  boost::weak_ptr<Model> model;
  std::string name;
  int handle;
  LinkPtr parent;
  LinkPtr child;
  JointLimits limits;
  double motorVel = 0.0;
  double motorFmax = 0.0;
};
}  // namespace physics
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::Contact, the contact points of two collisions
// as ContactSensor::Contacts(collision) returns them (made from a msgs::Contact, as Gazebo's operator= makes one).
// racebot has no physics::Collision objects: collision1 and collision2 stay null (Gazebo's point at the world's
// collisions); the names are in the msgs::Contact (ContactSensor::Contacts()).
#ifndef GAZEBO_PHYSICS_CONTACT_HH_
#define GAZEBO_PHYSICS_CONTACT_HH_

#include <string>

#include <ignition/math/Vector3.hh>

#include "gazebo/common/Time.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/JointWrench.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

// Gazebo's limit of contact points a Contact holds
#define MAX_CONTACT_JOINTS 32

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE Contact
{
public:
  Contact();
  Contact(const Contact &_contact) = default;
  virtual ~Contact() = default;
  Contact &operator=(const Contact &_contact) = default;
  // the points of the message (at most MAX_CONTACT_JOINTS), their wrenches, its time; the world by its name
  Contact &operator=(const msgs::Contact &_contact);
  void FillMsg(msgs::Contact &_msg) const;
  std::string DebugString() const;
  void Reset();

  Collision *collision1 = nullptr;
  Collision *collision2 = nullptr;
  JointWrench wrench[MAX_CONTACT_JOINTS];
  ignition::math::Vector3d positions[MAX_CONTACT_JOINTS];
  ignition::math::Vector3d normals[MAX_CONTACT_JOINTS];
  double depths[MAX_CONTACT_JOINTS];
  int count = 0;
  common::Time time;
  WorldPtr world;
};
}  // namespace physics
}  // namespace gazebo

#endif

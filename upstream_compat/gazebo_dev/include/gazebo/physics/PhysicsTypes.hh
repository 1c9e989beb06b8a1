// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the physics classes' pointer types, boost's as in
// Gazebo 11.
#ifndef GAZEBO_PHYSICS_PHYSICSTYPES_HH_
#define GAZEBO_PHYSICS_PHYSICSTYPES_HH_

#include "gazebo/common/CommonTypes.hh"
#include <vector>

#include "gazebo/util/bind.hh"
#include <boost/shared_ptr.hpp>
#include <boost/weak_ptr.hpp>
#include <boost/make_shared.hpp>

namespace gazebo
{
namespace physics
{
class World;
class Model;
class Link;
class Joint;
class PhysicsEngine;
class Inertial;
class MultiRayShape;
class Collision;  // declared only: racebot has no collision objects (physics/Contact.hh)
class Contact;

typedef boost::shared_ptr<World> WorldPtr;
typedef boost::shared_ptr<Model> ModelPtr;
typedef boost::shared_ptr<Link> LinkPtr;
typedef boost::shared_ptr<Joint> JointPtr;
typedef boost::shared_ptr<PhysicsEngine> PhysicsEnginePtr;
typedef boost::shared_ptr<Inertial> InertialPtr;
typedef boost::shared_ptr<MultiRayShape> MultiRayShapePtr;
typedef boost::shared_ptr<Collision> CollisionPtr;

typedef std::vector<ModelPtr> Model_V;
typedef std::vector<LinkPtr> Link_V;
typedef std::vector<JointPtr> Joint_V;
}  // namespace physics
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the physics classes a plugin includes at once.
#ifndef GAZEBO_PHYSICS_PHYSICS_HH_
#define GAZEBO_PHYSICS_PHYSICS_HH_

#include "gazebo/common/Console.hh"  // Gazebo's physics headers bring the console macros (gzlog in a RobotHWSim)
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/physics/PhysicsEngine.hh"
#include "gazebo/physics/World.hh"
#include "gazebo/physics/Model.hh"
#include "gazebo/physics/Inertial.hh"
#include "gazebo/physics/Link.hh"
#include "gazebo/physics/Joint.hh"
#include "gazebo/physics/JointController.hh"

#endif

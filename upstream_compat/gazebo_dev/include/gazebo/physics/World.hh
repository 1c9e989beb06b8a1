// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::World, what plugins read of it.
#ifndef GAZEBO_PHYSICS_WORLD_HH_
#define GAZEBO_PHYSICS_WORLD_HH_

#include <map>
#include <string>

#include <boost/enable_shared_from_this.hpp>
#include <ignition/math/Vector3.hh>

#include "gazebo/common/Time.hh"
#include "gazebo/physics/PhysicsEngine.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE World : public boost::enable_shared_from_this<World>
{
public:
  explicit World(const std::string &_name);
  std::string Name() const;
  std::string GetName() const { return this->Name(); }
  common::Time SimTime() const;
  common::Time GetSimTime() const { return this->SimTime(); }
  common::Time RealTime() const;
  PhysicsEnginePtr Physics() const;
  ignition::math::Vector3d Gravity() const;
  ModelPtr ModelByName(const std::string &_name) const;
  ModelPtr GetModel(const std::string &_name) const { return this->ModelByName(_name); }
  Model_V Models() const;
  unsigned int ModelCount() const;
  uint64_t Iterations() const;

  // racebot's host: the models it knows (added as they spawn, removed as they are deleted) and the update count.
  void AddModel(const ModelPtr &_model);
  void RemoveModel(const std::string &_name);
  void SetIterations(uint64_t _iterations);

private:
  std::string name;
  std::map<std::string, ModelPtr> models;
  PhysicsEnginePtr physics;
  uint64_t iterations = 0;
};

// The world by name ("": the first one). racebot has one world; an unknown name throws, as Gazebo's.
GZ_PHYSICS_VISIBLE WorldPtr get_world(const std::string &_name = "");
// racebot's host: sets the world get_world returns.
GZ_PHYSICS_VISIBLE void set_world(const WorldPtr &_world);
}  // namespace physics
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): sensors::ContactSensor (a <sensor type="contact">), as
// gazebo/sensors/ContactSensor.hh has it. While it is active, racebot reads the contacts of the sensor's
// <contact><collision>s after every physics step, as Gazebo's contact manager hands the sensor one message a step
// (gazebo_plugins/compiled_sensors.py: PyBullet's contact points, named and grouped as Gazebo names them, the force on
// the sensor's link in its frame about its centre of mass); at each update the sensor's Contacts() holds every
// contact of the steps since the previous update (at most the last 100 steps, as Gazebo keeps them), published as a
// msgs::Contacts on "~/<model>/<link>/<sensor>" to transport subscribers. A contact's wrench is body_1_wrench, the
// sensor's side (what gazebo_ros_bumper reads); body_2_wrench is not measured.
#ifndef GAZEBO_SENSORS_CONTACTSENSOR_HH_
#define GAZEBO_SENSORS_CONTACTSENSOR_HH_

#include <map>
#include <string>
#include <vector>

#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/Contact.hh"
#include "gazebo/sensors/Sensor.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace sensors
{
class GZ_SENSORS_VISIBLE ContactSensor : public Sensor
{
public:
  // racebot's host: `_collisions` the <contact><collision> names, as written (unscoped)
  ContactSensor(const Description &_description, const std::vector<std::string> &_collisions);

  // the monitored collisions, scoped: model::link::collision
  unsigned int GetCollisionCount() const;
  std::string GetCollisionName(const unsigned int _index) const;
  // the contact points of the last update that involve `_collisionName` (scoped)
  unsigned int GetCollisionContactCount(const std::string &_collisionName) const;
  msgs::Contacts Contacts() const;
  // the last update's contacts of `_collisionName` (scoped), by the other collision's name (collision pointers null)
  std::map<std::string, physics::Contact> Contacts(const std::string &_collisionName) const;
  // active, or somebody subscribes to its topic (Gazebo's ContactSensor::IsActive)
  bool IsActive() const override;
  // "~/<model>/<link>/<sensor>" (racebot's: Gazebo's sensor advertises there and has no Topic() of its own)
  std::string ContactsTopic() const;

  // racebot's host: one update at sim time `_time` from `_contacts`, every contact of the steps since the last one
  // (msgs::Contact each: collision1 the sensor's, positions, normals, depths, wrenches, the step's time; the host
  // calls it only after a step, as Gazebo updates only on new data). Publishes to the subscribers, then fires the
  // updated event.
  void Measure(const common::Time &_time, std::vector<msgs::Contact> _contacts);

private:
  std::vector<std::string> collisions;
  msgs::Contacts contactsMsg;
  const std::string topic;  // decoded
};
}  // namespace sensors
}  // namespace gazebo

#endif

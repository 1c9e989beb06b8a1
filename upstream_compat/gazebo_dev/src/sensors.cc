// racebot's Gazebo 11 plugin API: the sensor classes. Their data comes from racebot's host (Measure), which casts
// the rays and measures the IMUs in racebot's simulator; what they fire and report follows
// gazebo/sensors/RaySensor.cc, ImuSensor.cc and Sensor.cc.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <boost/make_shared.hpp>

#include "gazebo/common/Console.hh"
#include "gazebo/physics/Link.hh"
#include "gazebo/physics/Model.hh"
#include "gazebo/physics/MultiRayShape.hh"
#include "gazebo/physics/World.hh"
#include "gazebo/sensors/CameraSensor.hh"
#include "gazebo/sensors/ContactSensor.hh"
#include "gazebo/sensors/GpuRaySensor.hh"
#include "gazebo/sensors/ImuSensor.hh"
#include "gazebo/sensors/RaySensor.hh"
#include "gazebo/sensors/Sensor.hh"
#include "gazebo/transport/Node.hh"

namespace gazebo
{
namespace physics
{
double MultiRayShape::GetRange(unsigned int _index)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  if (_index >= this->ranges.size())
  {
    // Gazebo's MultiRayShape indexes its rays unchecked; here a clear error and the ray's full length
    gzerr << "MultiRayShape::GetRange: ray index " << _index << " out of range (" << this->RayCount()
          << " rays)\n";
    return this->geometry.maxRange;
  }
  return this->ranges[_index];
}

double MultiRayShape::GetRetro(unsigned int _index)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return _index < this->retro.size() ? this->retro[_index] : 0.0;
}

int MultiRayShape::GetFiducial(unsigned int /*_index*/) { return -1; }

unsigned int MultiRayShape::RayCount() const
{
  return static_cast<unsigned int>(std::max(1, this->geometry.samples) * std::max(1, this->geometry.verticalSamples));
}

void MultiRayShape::SetRays(std::vector<double> _ranges, std::vector<double> _retro)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->ranges = std::move(_ranges);
  this->retro = std::move(_retro);
}
}  // namespace physics

namespace sensors
{
Sensor::Sensor(const Description &_description, SensorCategory _category)
  : description(_description), category(_category), active(_description.alwaysOn)
{
}

Sensor::~Sensor() = default;

std::string Sensor::ScopedName() const
{
  return this->description.worldName + "::" + this->description.parentName + "::" + this->description.name;
}

double Sensor::UpdateRate() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->description.updateRate;
}

void Sensor::SetUpdateRate(const double _hz)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->description.updateRate = _hz > 0.0 && std::isfinite(_hz) ? _hz : 0.0;
}

ignition::math::Pose3d Sensor::Pose() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->description.pose;
}

void Sensor::SetPose(const ignition::math::Pose3d &_pose)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->description.pose = _pose;
}

void Sensor::SetActive(const bool _value)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->active = _value;
}

bool Sensor::IsActive() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->active;
}

common::Time Sensor::LastUpdateTime() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->lastUpdateTime;
}

common::Time Sensor::LastMeasurementTime() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->lastMeasurementTime;
}

event::ConnectionPtr Sensor::ConnectUpdated(std::function<void()> _subscriber)
{
  return this->updated.Connect(_subscriber);
}

void Sensor::ResetLastUpdateTime()
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->lastUpdateTime = common::Time::Zero;
}

void Sensor::Measured(const common::Time &_time)
{
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    this->lastMeasurementTime = _time;
    this->lastUpdateTime = _time;
  }
  this->updated();
}

namespace racebot
{
// "~/<parent, :: as />/<name>/<leaf>" ("" : no leaf), as Gazebo's sensors name their topics
std::string SensorTopic(const std::string &_parent, const std::string &_name, const std::string &_leaf)
{
  std::string topic = "~/" + _parent + "/" + _name + (_leaf.empty() ? "" : "/" + _leaf);
  for (std::string::size_type at = topic.find("::"); at != std::string::npos; at = topic.find("::", at))
    topic.replace(at, 2, "/");
  return topic;
}

RayScan::RayScan(const Description &_description, const physics::MultiRayShape::Geometry &_geometry)
  : Sensor(_description, RAY), geometry(_geometry),
    scanTopic(transport::racebot::DecodeTopicName(this->Topic(), _description.worldName))
{
  this->laserMsg.mutable_scan()->set_frame(_description.parentName);
}

std::string RayScan::Topic() const { return SensorTopic(this->ParentName(), this->Name(), "scan"); }

bool RayScan::IsActive() const
{
  return Sensor::IsActive() || transport::racebot::HasSubscribers(this->scanTopic);
}

int RayScan::RangeCount() const
{
  return std::max(1, static_cast<int>(std::round(this->geometry.samples * this->geometry.resolution)));
}

int RayScan::VerticalRangeCount() const
{
  return std::max(1, static_cast<int>(std::round(this->geometry.verticalSamples *
                                                 this->geometry.verticalResolution)));
}

double RayScan::AngleResolution() const
{
  return (this->AngleMax() - this->AngleMin()).Radian() / (this->RangeCount() - 1);
}

double RayScan::VerticalAngleResolution() const
{
  return (this->VerticalAngleMax() - this->VerticalAngleMin()).Radian() / (this->VerticalRangeCount() - 1);
}

void RayScan::Ranges(std::vector<double> &_ranges) const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  const auto &ranges = this->laserMsg.scan().ranges();
  _ranges.assign(ranges.begin(), ranges.end());
}

double RayScan::Range(const int _index) const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  const auto &scan = this->laserMsg.scan();
  if (scan.ranges_size() == 0)
  {
    gzwarn << "ranges not constructed yet (zero sized)\n";
    return 0.0;
  }
  if (_index < 0 || _index >= scan.ranges_size())
  {
    gzerr << "Invalid range index[" << _index << "]\n";
    return 0.0;
  }
  return scan.ranges(_index);
}

void RayScan::Measure(const common::Time &_time, const ignition::math::Pose3d &_worldPose,
                      std::vector<double> _ranges, std::vector<double> _intensities, std::vector<double> _rawRanges,
                      std::vector<double> _rawRetro)
{
  this->Cast(std::move(_rawRanges), std::move(_rawRetro));
  boost::shared_ptr<msgs::LaserScanStamped> stamped;  // a copy for the subscribers, made only when there are some
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    msgs::Set(this->laserMsg.mutable_time(), _time);
    msgs::LaserScan *scan = this->laserMsg.mutable_scan();
    msgs::Set(scan->mutable_world_pose(), _worldPose);
    scan->set_angle_min(this->AngleMin().Radian());
    scan->set_angle_max(this->AngleMax().Radian());
    scan->set_angle_step(this->AngleResolution());
    scan->set_count(this->RangeCount());
    scan->set_vertical_angle_min(this->VerticalAngleMin().Radian());
    scan->set_vertical_angle_max(this->VerticalAngleMax().Radian());
    scan->set_vertical_angle_step(this->VerticalAngleResolution());
    scan->set_vertical_count(this->VerticalRangeCount());
    scan->set_range_min(this->RangeMin());
    scan->set_range_max(this->RangeMax());
    scan->mutable_ranges()->Assign(std::move(_ranges));
    scan->mutable_intensities()->Assign(std::move(_intensities));
    if (transport::racebot::HasSubscribers(this->scanTopic))
      stamped = boost::make_shared<msgs::LaserScanStamped>(this->laserMsg);
  }
  if (stamped)
    transport::racebot::Deliver<msgs::LaserScanStamped>(this->scanTopic, stamped);
  this->Measured(_time);
}
}  // namespace racebot

RaySensor::RaySensor(const Description &_description, const physics::MultiRayShape::Geometry &_geometry)
  : racebot::RayScan(_description, _geometry), laserShape(boost::make_shared<physics::MultiRayShape>(_geometry))
{
}

double RaySensor::Retro(const int _index) const { return this->laserShape->GetRetro(_index); }

int RaySensor::Fiducial(const unsigned int _index) const { return this->laserShape->GetFiducial(_index); }

void RaySensor::Cast(std::vector<double> _rawRanges, std::vector<double> _rawRetro)
{
  this->laserShape->SetRays(std::move(_rawRanges), std::move(_rawRetro));
  this->laserShape->FireNewLaserScans();
}

GpuRaySensor::GpuRaySensor(const Description &_description, const physics::MultiRayShape::Geometry &_geometry)
  : racebot::RayScan(_description, _geometry)
{
}

event::ConnectionPtr GpuRaySensor::ConnectNewLaserFrame(LaserFrameCallback _subscriber)
{
  return this->newLaserFrame.Connect(_subscriber);
}

void GpuRaySensor::Cast(std::vector<double> _rawRanges, std::vector<double> _rawRetro)
{
  if (this->newLaserFrame.ConnectionCount() == 0)
    return;
  this->frame.assign(_rawRanges.size() * 3, 0.0f);
  for (size_t i = 0; i < _rawRanges.size(); ++i)
  {
    this->frame[i * 3] = static_cast<float>(_rawRanges[i]);
    this->frame[i * 3 + 1] = static_cast<float>(i < _rawRetro.size() ? _rawRetro[i] : 0.0);
  }
  this->newLaserFrame(this->frame.data(), static_cast<unsigned int>(this->RayCount()),
                      static_cast<unsigned int>(this->VerticalRayCount()), 3u, std::string("BLAH"));
}

namespace
{
physics::LinkPtr ParentLink(const Sensor::Description &_description)
{
  const std::string &scoped = _description.parentName;
  const std::string::size_type at = scoped.find("::");
  physics::WorldPtr world = physics::get_world();
  physics::ModelPtr model = world && at != std::string::npos ? world->ModelByName(scoped.substr(0, at)) : nullptr;
  physics::LinkPtr link = model ? model->GetLink(scoped.substr(at + 2)) : nullptr;
  if (!link)
    throw std::runtime_error("IMU has invalid parent[" + scoped + "]. Must be a link");
  return link;
}
}  // namespace

ImuSensor::ImuSensor(const Description &_description)
  : Sensor(_description, OTHER), parent(ParentLink(_description)),
    imuTopic(transport::racebot::DecodeTopicName(racebot::SensorTopic(_description.parentName, _description.name,
                                                                      "imu"), _description.worldName))
{
  msgs::Set(this->imuMsg.mutable_orientation(), ignition::math::Quaterniond::Identity);
  // Gazebo's Load: the reference is the sensor's own frame as it was made
  this->worldToReference = this->WorldPose().Rot();
}

ignition::math::Pose3d ImuSensor::WorldPose() const { return this->Pose() + this->parent->WorldPose(); }

msgs::IMU ImuSensor::ImuMessage() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->imuMsg;
}

ignition::math::Vector3d ImuSensor::AngularVelocity(const bool _noiseFree) const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return _noiseFree ? this->angularVel : msgs::ConvertIgn(this->imuMsg.angular_velocity());
}

ignition::math::Vector3d ImuSensor::LinearAcceleration(const bool _noiseFree) const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return _noiseFree ? this->linearAcc : msgs::ConvertIgn(this->imuMsg.linear_acceleration());
}

ignition::math::Quaterniond ImuSensor::Orientation() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return msgs::ConvertIgn(this->imuMsg.orientation());
}

void ImuSensor::SetReferencePose() { this->SetWorldToReferenceOrientation(this->WorldPose().Rot()); }

void ImuSensor::SetWorldToReferenceOrientation(const ignition::math::Quaterniond &_orientation)
{
  std::lock_guard<std::mutex> lock(this->mutex);
  this->worldToReference = _orientation;
}

bool ImuSensor::IsActive() const
{
  return Sensor::IsActive() || transport::racebot::HasSubscribers(this->imuTopic);
}

void ImuSensor::Measure(const common::Time &_time, const ignition::math::Pose3d &_worldPose,
                        const ignition::math::Vector3d &_angularVel, const ignition::math::Vector3d &_linearAcc,
                        const ignition::math::Vector3d &_noisyAngularVel,
                        const ignition::math::Vector3d &_noisyLinearAcc)
{
  boost::shared_ptr<msgs::IMU> copy;  // for the subscribers, made only when there are some
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    this->imuMsg.set_entity_name(this->description.parentName);
    msgs::Set(this->imuMsg.mutable_stamp(), _time);
    this->angularVel = _angularVel;
    this->linearAcc = _linearAcc;
    msgs::Set(this->imuMsg.mutable_angular_velocity(), _noisyAngularVel);
    msgs::Set(this->imuMsg.mutable_linear_acceleration(), _noisyLinearAcc);
    msgs::Set(this->imuMsg.mutable_orientation(), this->worldToReference.Inverse() * _worldPose.Rot());
    if (transport::racebot::HasSubscribers(this->imuTopic))
      copy = boost::make_shared<msgs::IMU>(this->imuMsg);
  }
  if (copy)
    transport::racebot::Deliver<msgs::IMU>(this->imuTopic, copy);
  this->Measured(_time);
}

ContactSensor::ContactSensor(const Description &_description, const std::vector<std::string> &_collisions)
  : Sensor(_description, OTHER),
    topic(transport::racebot::DecodeTopicName(racebot::SensorTopic(_description.parentName, _description.name, ""),
                                              _description.worldName))
{
  for (const auto &name : _collisions)
    this->collisions.push_back(_description.parentName + "::" + name);
}

unsigned int ContactSensor::GetCollisionCount() const { return static_cast<unsigned int>(this->collisions.size()); }

std::string ContactSensor::GetCollisionName(const unsigned int _index) const
{
  return _index < this->collisions.size() ? this->collisions[_index] : std::string();
}

unsigned int ContactSensor::GetCollisionContactCount(const std::string &_collisionName) const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  unsigned int result = 0;
  for (int i = 0; i < this->contactsMsg.contact_size(); ++i)
  {
    const msgs::Contact &contact = this->contactsMsg.contact(i);
    if (contact.collision1() == _collisionName || contact.collision2() == _collisionName)
      result += static_cast<unsigned int>(contact.position_size());
  }
  return result;
}

msgs::Contacts ContactSensor::Contacts() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->contactsMsg;
}

std::map<std::string, physics::Contact> ContactSensor::Contacts(const std::string &_collisionName) const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  std::map<std::string, physics::Contact> result;
  for (int i = 0; i < this->contactsMsg.contact_size(); ++i)
  {
    const msgs::Contact &contact = this->contactsMsg.contact(i);
    std::string other;
    if (contact.collision1() == _collisionName)
      other = contact.collision2();
    else if (contact.collision2() == _collisionName)
      other = contact.collision1();
    if (!other.empty())
      result[other] = contact;
  }
  return result;
}

bool ContactSensor::IsActive() const
{
  return Sensor::IsActive() || transport::racebot::HasSubscribers(this->topic);
}

std::string ContactSensor::ContactsTopic() const { return racebot::SensorTopic(this->ParentName(), this->Name(), ""); }

void ContactSensor::Measure(const common::Time &_time, std::vector<msgs::Contact> _contacts)
{
  boost::shared_ptr<msgs::Contacts> copy;
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    this->contactsMsg.clear_contact();
    for (auto &contact : _contacts)
    {
      const int count = contact.position_size();
      if (count != contact.normal_size() || count != contact.wrench_size() || count != contact.depth_size())
      {
        gzerr << "Contact message has invalid array sizes\n";
        continue;
      }
      *this->contactsMsg.add_contact() = std::move(contact);
    }
    msgs::Set(this->contactsMsg.mutable_time(), _time);
    if (transport::racebot::HasSubscribers(this->topic))
      copy = boost::make_shared<msgs::Contacts>(this->contactsMsg);
  }
  if (copy)
    transport::racebot::Deliver<msgs::Contacts>(this->topic, copy);
  this->Measured(_time);
}

CameraSensor::CameraSensor(const Description &_description, rendering::CameraPtr _camera)
  : Sensor(_description, IMAGE), camera(std::move(_camera))
{
}

std::string CameraSensor::Topic() const { return racebot::SensorTopic(this->ParentName(), this->Name(), "image"); }

bool CameraSensor::Rendered() const
{
  std::lock_guard<std::mutex> lock(this->mutex);
  return this->rendered;
}

void CameraSensor::Measure(const common::Time &_time, const ignition::math::Pose3d &_worldPose,
                           std::vector<unsigned char> _data)
{
  {
    std::lock_guard<std::mutex> lock(this->mutex);
    this->rendered = true;
    this->lastMeasurementTime = _time;  // what OnNewFrame reads (gazebo_ros_camera stamps with it)
  }
  this->camera->Frame(_worldPose, std::move(_data));
  this->Measured(_time);
}
}  // namespace sensors
}  // namespace gazebo

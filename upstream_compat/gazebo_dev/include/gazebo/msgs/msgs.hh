// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the Gazebo messages a sensor plugin reads, with the
// field names and accessors of Gazebo's .proto files (time, vector3d, quaternion, pose, laserscan,
// laserscan_stamped, imu, wrench, joint_wrench, contact, contacts) as protobuf generates them (`scan().ranges(i)`, `ranges_size()`, `mutable_scan()`,
// `set_count(n)`, ...), and gazebo/msgs/msgs.hh's Set and Convert for them. Plain C++ classes, not protobuf: racebot
// has no Gazebo transport process, so nothing is serialized (transport/Node.hh delivers them in the world server).
#ifndef GAZEBO_MSGS_MSGS_HH_
#define GAZEBO_MSGS_MSGS_HH_

#include <cstdint>
#include <string>
#include <vector>

#include <ignition/math/Pose3.hh>
#include <ignition/math/Quaternion.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/common/Time.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace msgs
{
// A repeated field as protobuf's RepeatedField<T> reads: size, index, data, iteration.
template<typename T>
class RepeatedField
{
public:
  int size() const { return static_cast<int>(this->values.size()); }
  const T &Get(int _index) const { return this->values.at(_index); }
  const T &operator[](int _index) const { return this->values[_index]; }
  T *Mutable(int _index) { return &this->values.at(_index); }
  void Set(int _index, const T &_value) { this->values.at(_index) = _value; }
  void Add(const T &_value) { this->values.push_back(_value); }
  void Clear() { this->values.clear(); }
  void Reserve(int _n) { this->values.reserve(_n); }
  const T *data() const { return this->values.data(); }
  T *mutable_data() { return this->values.data(); }
  typename std::vector<T>::const_iterator begin() const { return this->values.begin(); }
  typename std::vector<T>::const_iterator end() const { return this->values.end(); }
  // racebot's: the values at once
  void Assign(std::vector<T> _values) { this->values = std::move(_values); }

private:
  std::vector<T> values;
};

// One scalar field: `name()`, `set_name(v)`, `has_name()`, `clear_name()`.
#define RACEBOT_MSG_FIELD(type, name, initial) \
public: \
  type name() const { return this->name##_; } \
  void set_##name(type _value) { this->name##_ = _value; this->has_##name##_ = true; } \
  bool has_##name() const { return this->has_##name##_; } \
  void clear_##name() { this->name##_ = initial; this->has_##name##_ = false; } \
private: \
  type name##_ = initial; \
  bool has_##name##_ = false;

// One string field: `name()`, `set_name(v)`, `mutable_name()`.
#define RACEBOT_MSG_STRING(name) \
public: \
  const std::string &name() const { return this->name##_; } \
  void set_##name(const std::string &_value) { this->name##_ = _value; } \
  std::string *mutable_##name() { return &this->name##_; } \
private: \
  std::string name##_;

// One message field: `name()`, `mutable_name()`, `has_name()`.
#define RACEBOT_MSG_MESSAGE(type, name) \
public: \
  const type &name() const { return this->name##_; } \
  type *mutable_##name() { this->has_##name##_ = true; return &this->name##_; } \
  bool has_##name() const { return this->has_##name##_; } \
private: \
  type name##_; \
  bool has_##name##_ = false;

// One repeated scalar field: `name(i)`, `name_size()`, `name()`, `add_name(v)`, `set_name(i, v)`, `clear_name()`,
// `mutable_name()`.
#define RACEBOT_MSG_REPEATED(type, name) \
public: \
  type name(int _index) const { return this->name##_.Get(_index); } \
  int name##_size() const { return this->name##_.size(); } \
  const RepeatedField<type> &name() const { return this->name##_; } \
  RepeatedField<type> *mutable_##name() { return &this->name##_; } \
  void add_##name(type _value) { this->name##_.Add(_value); } \
  void set_##name(int _index, type _value) { this->name##_.Set(_index, _value); } \
  void clear_##name() { this->name##_.Clear(); } \
private: \
  RepeatedField<type> name##_;

// One repeated message field: `name(i)`, `name_size()`, `name()`, `add_name()`, `mutable_name(i)`, `clear_name()`.
#define RACEBOT_MSG_REPEATED_MESSAGE(type, name) \
public: \
  const type &name(int _index) const { return this->name##_.Get(_index); } \
  int name##_size() const { return this->name##_.size(); } \
  const RepeatedField<type> &name() const { return this->name##_; } \
  type *add_##name() { this->name##_.Add(type()); return this->name##_.Mutable(this->name##_.size() - 1); } \
  type *mutable_##name(int _index) { return this->name##_.Mutable(_index); } \
  void clear_##name() { this->name##_.Clear(); } \
private: \
  RepeatedField<type> name##_;

class GZ_UTIL_VISIBLE Time
{
  RACEBOT_MSG_FIELD(int32_t, sec, 0)
  RACEBOT_MSG_FIELD(int32_t, nsec, 0)
};

class GZ_UTIL_VISIBLE Vector3d
{
  RACEBOT_MSG_FIELD(double, x, 0.0)
  RACEBOT_MSG_FIELD(double, y, 0.0)
  RACEBOT_MSG_FIELD(double, z, 0.0)
};

class GZ_UTIL_VISIBLE Quaternion
{
  RACEBOT_MSG_FIELD(double, x, 0.0)
  RACEBOT_MSG_FIELD(double, y, 0.0)
  RACEBOT_MSG_FIELD(double, z, 0.0)
  RACEBOT_MSG_FIELD(double, w, 1.0)
};

class GZ_UTIL_VISIBLE Pose
{
public:
  const std::string &name() const { return this->name_; }
  void set_name(const std::string &_name) { this->name_ = _name; }
  RACEBOT_MSG_FIELD(uint32_t, id, 0)
  RACEBOT_MSG_MESSAGE(Vector3d, position)
  RACEBOT_MSG_MESSAGE(Quaternion, orientation)

private:
  std::string name_;
};

// laserscan.proto: a ray sensor's scan, ranges and intensities index i + j * count (horizontal fastest)
class GZ_UTIL_VISIBLE LaserScan
{
public:
  const std::string &frame() const { return this->frame_; }
  void set_frame(const std::string &_frame) { this->frame_ = _frame; }
  RACEBOT_MSG_MESSAGE(Pose, world_pose)
  RACEBOT_MSG_FIELD(double, angle_min, 0.0)
  RACEBOT_MSG_FIELD(double, angle_max, 0.0)
  RACEBOT_MSG_FIELD(double, angle_step, 0.0)
  RACEBOT_MSG_FIELD(double, range_min, 0.0)
  RACEBOT_MSG_FIELD(double, range_max, 0.0)
  RACEBOT_MSG_FIELD(uint32_t, count, 0)
  RACEBOT_MSG_FIELD(double, vertical_angle_min, 0.0)
  RACEBOT_MSG_FIELD(double, vertical_angle_max, 0.0)
  RACEBOT_MSG_FIELD(double, vertical_angle_step, 0.0)
  RACEBOT_MSG_FIELD(uint32_t, vertical_count, 0)
  RACEBOT_MSG_REPEATED(double, ranges)
  RACEBOT_MSG_REPEATED(double, intensities)

private:
  std::string frame_;
};

// laserscan_stamped.proto: what a RaySensor publishes on its Topic()
class GZ_UTIL_VISIBLE LaserScanStamped
{
  RACEBOT_MSG_MESSAGE(Time, time)
  RACEBOT_MSG_MESSAGE(LaserScan, scan)
};

// imu.proto: what an ImuSensor publishes on its topic (~/<model>/<link>/<sensor>/imu) and ImuMessage() returns
class GZ_UTIL_VISIBLE IMU
{
public:
  const std::string &entity_name() const { return this->entity_name_; }
  void set_entity_name(const std::string &_name) { this->entity_name_ = _name; }
  RACEBOT_MSG_MESSAGE(Time, stamp)
  RACEBOT_MSG_MESSAGE(Quaternion, orientation)
  RACEBOT_MSG_MESSAGE(Vector3d, angular_velocity)
  RACEBOT_MSG_MESSAGE(Vector3d, linear_acceleration)

private:
  std::string entity_name_;
};

// wrench.proto
class GZ_UTIL_VISIBLE Wrench
{
  RACEBOT_MSG_MESSAGE(Vector3d, force)
  RACEBOT_MSG_MESSAGE(Vector3d, torque)
  RACEBOT_MSG_MESSAGE(Vector3d, force_offset)
};

// joint_wrench.proto: a contact point's wrench on each body (body_1: the collision1 side)
class GZ_UTIL_VISIBLE JointWrench
{
  RACEBOT_MSG_STRING(body_1_name)
  RACEBOT_MSG_FIELD(uint32_t, body_1_id, 0)
  RACEBOT_MSG_STRING(body_2_name)
  RACEBOT_MSG_FIELD(uint32_t, body_2_id, 0)
  RACEBOT_MSG_MESSAGE(Wrench, body_1_wrench)
  RACEBOT_MSG_MESSAGE(Wrench, body_2_wrench)
};

// contact.proto: the contact points of two collisions (scoped names, model::link::collision), one entry each in
// position, normal, depth and wrench
class GZ_UTIL_VISIBLE Contact
{
  RACEBOT_MSG_STRING(collision1)
  RACEBOT_MSG_STRING(collision2)
  RACEBOT_MSG_REPEATED_MESSAGE(Vector3d, position)
  RACEBOT_MSG_REPEATED_MESSAGE(Vector3d, normal)
  RACEBOT_MSG_REPEATED(double, depth)
  RACEBOT_MSG_REPEATED_MESSAGE(JointWrench, wrench)
  RACEBOT_MSG_MESSAGE(Time, time)
  RACEBOT_MSG_STRING(world)
};

// contacts.proto: what a ContactSensor publishes on its topic and Contacts() returns
class GZ_UTIL_VISIBLE Contacts
{
  RACEBOT_MSG_REPEATED_MESSAGE(Contact, contact)
  RACEBOT_MSG_MESSAGE(Time, time)
};

#undef RACEBOT_MSG_FIELD
#undef RACEBOT_MSG_STRING
#undef RACEBOT_MSG_REPEATED_MESSAGE
#undef RACEBOT_MSG_MESSAGE
#undef RACEBOT_MSG_REPEATED

// gazebo/msgs/msgs.hh's conversions for these messages
GZ_UTIL_VISIBLE void Set(Time *_t, const common::Time &_v);
GZ_UTIL_VISIBLE void Set(Vector3d *_pt, const ignition::math::Vector3d &_v);
GZ_UTIL_VISIBLE void Set(Quaternion *_q, const ignition::math::Quaterniond &_v);
GZ_UTIL_VISIBLE void Set(Pose *_p, const ignition::math::Pose3d &_v);
GZ_UTIL_VISIBLE Time Convert(const common::Time &_t);
GZ_UTIL_VISIBLE common::Time Convert(const Time &_t);
GZ_UTIL_VISIBLE Vector3d Convert(const ignition::math::Vector3d &_v);
GZ_UTIL_VISIBLE Quaternion Convert(const ignition::math::Quaterniond &_q);
GZ_UTIL_VISIBLE Pose Convert(const ignition::math::Pose3d &_p);
GZ_UTIL_VISIBLE ignition::math::Vector3d ConvertIgn(const Vector3d &_v);
GZ_UTIL_VISIBLE ignition::math::Quaterniond ConvertIgn(const Quaternion &_q);
GZ_UTIL_VISIBLE ignition::math::Pose3d ConvertIgn(const Pose &_p);
}  // namespace msgs
}  // namespace gazebo

#include "gazebo/msgs/MessageTypes.hh"

#endif

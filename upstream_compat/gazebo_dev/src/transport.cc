// racebot's Gazebo 11 plugin API: transport::Node's subscriptions, kept in the world server, and the messages'
// Set and Convert (gazebo/msgs/msgs.hh).
#include <map>
#include <mutex>
#include <set>
#include <utility>
#include <vector>

#include "gazebo/common/Console.hh"
#include "gazebo/common/Event.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/World.hh"
#include "gazebo/transport/Node.hh"
#include "gazebo/transport/Subscriber.hh"

namespace gazebo
{
namespace transport
{
namespace racebot
{
namespace
{
struct Subscription
{
  std::string topic;
  std::string type;
  int owner;
  Callback callback;
};

std::mutex mutex;
std::map<int, Subscription> subscriptions;
std::set<std::pair<std::string, std::string>> mismatchesSaid;
int lastId = 0;
}  // namespace

int AddSubscription(const std::string &_topic, const std::string &_type, Callback _callback)
{
  std::lock_guard<std::mutex> lock(mutex);
  const int id = ++lastId;
  subscriptions[id] = Subscription{_topic, _type, event::detail::CurrentOwner(), std::move(_callback)};
  return id;
}

void RemoveSubscription(int _id)
{
  Callback dropped;  // destroyed after the lock: a callback's captures may unsubscribe in their destructors
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto found = subscriptions.find(_id);
    if (found == subscriptions.end())
      return;
    dropped = std::move(found->second.callback);
    subscriptions.erase(found);
  }
}

void RemoveOwnerSubscriptions(int _owner)
{
  std::vector<Callback> dropped;
  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = subscriptions.begin(); it != subscriptions.end();)
  {
    if (it->second.owner == _owner)
    {
      dropped.push_back(std::move(it->second.callback));
      it = subscriptions.erase(it);
    }
    else
      ++it;
  }
}

bool HasSubscribers(const std::string &_topic)
{
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto &entry : subscriptions)
    if (entry.second.topic == _topic)
      return true;
  return false;
}

void Deliver(const std::string &_topic, const std::string &_type, const boost::shared_ptr<const void> &_msg)
{
  std::vector<Subscription> receivers;  // a copy: a callback may subscribe or unsubscribe
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto &entry : subscriptions)
    {
      if (entry.second.topic != _topic)
        continue;
      if (entry.second.type != _type)
      {
        if (mismatchesSaid.insert({_topic, entry.second.type}).second)
          gzerr << "racebot: a subscriber of " << _topic << " takes messages of type " << entry.second.type
                << ", but the topic carries " << _type << ": it gets none\n";
        continue;
      }
      receivers.push_back(entry.second);
    }
  }
  for (const auto &receiver : receivers)
  {
    event::detail::OwnerScope scope(receiver.owner);
    try
    {
      receiver.callback(_msg);
    }
    catch (const std::exception &_e)
    {
      event::detail::ReportFailure(receiver.owner, std::string("in its subscriber of ") + _topic + ": " + _e.what());
    }
    catch (...)
    {
      event::detail::ReportFailure(receiver.owner, "in its subscriber of " + _topic +
                                                   ": an exception that is not a std::exception");
    }
  }
}

std::string DecodeTopicName(const std::string &_topic, const std::string &_space)
{
  const std::string prefix = "/gazebo/" + _space;
  if (_topic.compare(0, 1, "~") == 0)
    return prefix + _topic.substr(1);
  if (_topic.compare(0, 1, "/") == 0)
    return _topic;
  return prefix + "/" + _topic;
}
}  // namespace racebot

Node::Node() = default;

Node::~Node() { this->Fini(); }

void Node::Init(const std::string &_space)
{
  std::string space = _space;
  if (space.empty())
  {
    physics::WorldPtr world;
    try
    {
      world = physics::get_world();
    }
    catch (const std::exception &)
    {
    }
    space = world ? world->Name() : "default";
  }
  this->topicNamespace = space;
  this->initialized = true;
}

void Node::Fini() { this->initialized = false; }

std::string Node::GetTopicNamespace() const { return this->topicNamespace; }

std::string Node::DecodeTopicName(const std::string &_topic)
{
  return racebot::DecodeTopicName(_topic, this->topicNamespace);
}

std::string Node::EncodeTopicName(const std::string &_topic)
{
  const std::string prefix = "/gazebo/" + this->topicNamespace;
  if (_topic.compare(0, prefix.size(), prefix) == 0)
    return "~" + _topic.substr(prefix.size());
  return _topic;
}

Subscriber::Subscriber(const std::string &_topic, int _id) : topic(_topic), id(_id) {}

Subscriber::~Subscriber() { this->Unsubscribe(); }

void Subscriber::Unsubscribe() const
{
  if (this->id > 0)
    racebot::RemoveSubscription(this->id);
  this->id = 0;
}
}  // namespace transport

namespace msgs
{
void Set(Time *_t, const common::Time &_v)
{
  _t->set_sec(_v.sec);
  _t->set_nsec(_v.nsec);
}

void Set(Vector3d *_pt, const ignition::math::Vector3d &_v)
{
  _pt->set_x(_v.X());
  _pt->set_y(_v.Y());
  _pt->set_z(_v.Z());
}

void Set(Quaternion *_q, const ignition::math::Quaterniond &_v)
{
  _q->set_x(_v.X());
  _q->set_y(_v.Y());
  _q->set_z(_v.Z());
  _q->set_w(_v.W());
}

void Set(Pose *_p, const ignition::math::Pose3d &_v)
{
  Set(_p->mutable_position(), _v.Pos());
  Set(_p->mutable_orientation(), _v.Rot());
}

Time Convert(const common::Time &_t)
{
  Time result;
  Set(&result, _t);
  return result;
}

common::Time Convert(const Time &_t) { return common::Time(_t.sec(), _t.nsec()); }

Vector3d Convert(const ignition::math::Vector3d &_v)
{
  Vector3d result;
  Set(&result, _v);
  return result;
}

Quaternion Convert(const ignition::math::Quaterniond &_q)
{
  Quaternion result;
  Set(&result, _q);
  return result;
}

Pose Convert(const ignition::math::Pose3d &_p)
{
  Pose result;
  Set(&result, _p);
  return result;
}

ignition::math::Vector3d ConvertIgn(const Vector3d &_v) { return ignition::math::Vector3d(_v.x(), _v.y(), _v.z()); }

ignition::math::Quaterniond ConvertIgn(const Quaternion &_q)
{
  return ignition::math::Quaterniond(_q.w(), _q.x(), _q.y(), _q.z());
}

ignition::math::Pose3d ConvertIgn(const Pose &_p)
{
  return ignition::math::Pose3d(ConvertIgn(_p.position()), ConvertIgn(_p.orientation()));
}
}  // namespace msgs
}  // namespace gazebo

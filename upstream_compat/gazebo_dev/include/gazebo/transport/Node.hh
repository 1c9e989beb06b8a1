// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): transport::Node's subscriptions, inside the world
// server. Gazebo's transport carries messages between gzserver's threads (and processes) through a master; a
// plugin uses it to read its sensor: `node->Init(); sub = node->Subscribe(sensor->Topic(), &X::OnScan, this);`.
// racebot has one process and no transport master: a subscription is kept here, and racebot's sensors hand each
// message to the subscribers of their topic at once, on the thread that measured it (Gazebo: on a transport thread
// soon after). Topic names are decoded as Gazebo decodes them ("~" is /gazebo/<the node's namespace>, which Init("")
// makes the world's name). Advertise and publishing from a plugin are not provided (docs/SUPPORTED.md).
#ifndef GAZEBO_TRANSPORT_NODE_HH_
#define GAZEBO_TRANSPORT_NODE_HH_

#include <functional>
#include <memory>
#include <string>
#include <typeinfo>

#include <boost/enable_shared_from_this.hpp>
#include <boost/shared_ptr.hpp>

#include "gazebo/msgs/MessageTypes.hh"
#include "gazebo/transport/Subscriber.hh"
#include "gazebo/transport/TransportTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace transport
{
namespace racebot
{
// A subscriber's callback, type-erased: it is handed the message as the type it subscribed with.
typedef std::function<void(const boost::shared_ptr<const void> &)> Callback;
// Adds a subscription to the (decoded) topic for messages of `_type` (typeid(M).name()); returns its id.
GZ_UTIL_VISIBLE int AddSubscription(const std::string &_topic, const std::string &_type, Callback _callback);
GZ_UTIL_VISIBLE void RemoveSubscription(int _id);
// racebot's sensors: whether anybody subscribes to the (decoded) topic, and handing them a message (each
// subscriber's callback under the plugin that subscribed, as event callbacks: one that throws is reported against
// it, gazebo/common/Event.hh). A subscriber of another message type is skipped, with one error naming both types.
GZ_UTIL_VISIBLE bool HasSubscribers(const std::string &_topic);
GZ_UTIL_VISIBLE void Deliver(const std::string &_topic, const std::string &_type,
                             const boost::shared_ptr<const void> &_msg);
template<typename M>
void Deliver(const std::string &_topic, const boost::shared_ptr<M const> &_msg)
{
  Deliver(_topic, typeid(M).name(), boost::static_pointer_cast<const void>(_msg));
}
// The subscriptions a plugin made (racebot's host, when it unloads the plugin).
GZ_UTIL_VISIBLE void RemoveOwnerSubscriptions(int _owner);
// "~/x" and "x" under /gazebo/<_space>, as Node::DecodeTopicName
GZ_UTIL_VISIBLE std::string DecodeTopicName(const std::string &_topic, const std::string &_space);
}  // namespace racebot

class GZ_UTIL_VISIBLE Node : public boost::enable_shared_from_this<Node>
{
public:
  Node();
  virtual ~Node();
  // `_space`: the topic namespace ("": the world's name, as Gazebo's first world)
  void Init(const std::string &_space = "");
  void Fini();
  std::string GetTopicNamespace() const;
  // "~/a/b" -> "/gazebo/<namespace>/a/b"; "a/b" -> "/gazebo/<namespace>/a/b"; "/a/b" stays
  std::string DecodeTopicName(const std::string &_topic);
  std::string EncodeTopicName(const std::string &_topic);
  bool IsInitialized() const { return this->initialized; }

  template<typename M, typename T>
  SubscriberPtr Subscribe(const std::string &_topic, void (T::*_fp)(const boost::shared_ptr<M const> &), T *_obj,
                          bool _latching = false)
  {
    return this->Subscribe<M>(_topic, std::function<void(const boost::shared_ptr<M const> &)>(
                                          [_fp, _obj](const boost::shared_ptr<M const> &_msg) { (_obj->*_fp)(_msg); }),
                              _latching);
  }

  template<typename M>
  SubscriberPtr Subscribe(const std::string &_topic, void (*_fp)(const boost::shared_ptr<M const> &),
                          bool _latching = false)
  {
    return this->Subscribe<M>(_topic, std::function<void(const boost::shared_ptr<M const> &)>(_fp), _latching);
  }

  template<typename M>
  SubscriberPtr Subscribe(const std::string &_topic, std::function<void(const boost::shared_ptr<M const> &)> _cb,
                          bool /*_latching*/ = false)
  {
    const std::string topic = this->DecodeTopicName(_topic);
    const int id = racebot::AddSubscription(topic, typeid(M).name(),
                                            [_cb](const boost::shared_ptr<const void> &_msg) {
                                              _cb(boost::static_pointer_cast<M const>(_msg));
                                            });
    return SubscriberPtr(new Subscriber(topic, id));
  }

private:
  std::string topicNamespace;
  bool initialized = false;
};
}  // namespace transport
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): transport::Subscriber, what Node::Subscribe returns.
// The subscription lasts until Unsubscribe() or the last copy of its SubscriberPtr goes, as Gazebo's.
#ifndef GAZEBO_TRANSPORT_SUBSCRIBER_HH_
#define GAZEBO_TRANSPORT_SUBSCRIBER_HH_

#include <string>

#include "gazebo/util/system.hh"

namespace gazebo
{
namespace transport
{
class GZ_UTIL_VISIBLE Subscriber
{
public:
  Subscriber(const std::string &_topic, int _id);
  virtual ~Subscriber();
  std::string GetTopic() const { return this->topic; }
  void Unsubscribe() const;
  unsigned int Id() const { return static_cast<unsigned int>(this->id); }

private:
  std::string topic;
  mutable int id;
};
}  // namespace transport
}  // namespace gazebo

#endif

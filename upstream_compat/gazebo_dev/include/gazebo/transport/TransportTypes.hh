// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): Gazebo transport's pointer types, which plugins'
// headers include (gazebo_ros_pkgs' plugins among them) without using them. racebot has no Gazebo transport: a
// plugin that creates a transport::Node does not build (docs/SUPPORTED.md).
#ifndef GAZEBO_TRANSPORT_TRANSPORTTYPES_HH_
#define GAZEBO_TRANSPORT_TRANSPORTTYPES_HH_

#include <boost/shared_ptr.hpp>

namespace gazebo
{
namespace transport
{
class Node;
class Publisher;
class Subscriber;
typedef boost::shared_ptr<Node> NodePtr;
typedef boost::shared_ptr<Publisher> PublisherPtr;
typedef boost::shared_ptr<Subscriber> SubscriberPtr;
}  // namespace transport
}  // namespace gazebo

#endif

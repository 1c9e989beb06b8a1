// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): Gazebo transport's pointer types, which plugins'
// headers include (gazebo_ros_pkgs' plugins among them). What racebot's transport has: transport/Node.hh.
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

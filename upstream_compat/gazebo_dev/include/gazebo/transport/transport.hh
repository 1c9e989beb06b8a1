// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): what `#include <gazebo/transport/transport.hh>` gives.
#ifndef GAZEBO_TRANSPORT_TRANSPORT_HH_
#define GAZEBO_TRANSPORT_TRANSPORT_HH_

#include "gazebo/transport/Node.hh"
#include "gazebo/transport/Subscriber.hh"
#include "gazebo/transport/TransportTypes.hh"

#endif

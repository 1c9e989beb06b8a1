// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): what `#include <gazebo/gazebo.hh>` gives a plugin.
#ifndef GAZEBO_GAZEBO_HH_
#define GAZEBO_GAZEBO_HH_

// Gazebo 11's headers bring boost::bind with its global placeholders (Boost 1.71's <boost/bind.hpp>): plugins
// write ConnectWorldUpdateBegin(boost::bind(&X::OnUpdate, this, _1)) and build. Debian's Boost 1.74 keeps them
// global only when asked.
#ifndef BOOST_BIND_GLOBAL_PLACEHOLDERS
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#endif
#include <boost/bind.hpp>

#include "gazebo/gazebo_config.h"
#include "gazebo/common/common.hh"
#include "gazebo/physics/physics.hh"

#endif

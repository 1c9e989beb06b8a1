// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): what `#include <gazebo/gazebo.hh>` gives a plugin.
#ifndef GAZEBO_GAZEBO_HH_
#define GAZEBO_GAZEBO_HH_

#include "gazebo/util/bind.hh"  // boost::bind's global placeholders, as Gazebo 11's headers bring them

#include "gazebo/gazebo_config.h"
#include "gazebo/common/common.hh"
#include "gazebo/physics/physics.hh"

#endif

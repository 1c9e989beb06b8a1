// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the common classes a plugin includes at once.
#ifndef GAZEBO_COMMON_COMMON_HH_
#define GAZEBO_COMMON_COMMON_HH_

#include "gazebo/common/Console.hh"
#include "gazebo/common/Event.hh"
#include "gazebo/common/Events.hh"
#include "gazebo/common/Exception.hh"
#include "gazebo/common/PID.hh"
#include "gazebo/common/Plugin.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/common/UpdateInfo.hh"

#endif

// racebot overlay of pluginlib (upstream_compat/pluginlib): ROS 1's <pluginlib/class_desc.h>, Noetic's name of
// <pluginlib/class_desc.hpp>, which Debian's pluginlib 5.2 has and this one no longer.
#ifndef RACEBOT_PLUGINLIB_CLASS_DESC_H_
#define RACEBOT_PLUGINLIB_CLASS_DESC_H_

#include <pluginlib/class_desc.hpp>

#endif  // RACEBOT_PLUGINLIB_CLASS_DESC_H_

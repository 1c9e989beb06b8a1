// racebot overlay of pluginlib (upstream_compat/pluginlib): ROS 1's <pluginlib/class_loader.h>, Noetic's name of
// <pluginlib/class_loader.hpp>, which Debian's pluginlib 5.2 has and this one no longer.
#ifndef RACEBOT_PLUGINLIB_CLASS_LOADER_H_
#define RACEBOT_PLUGINLIB_CLASS_LOADER_H_

#include <pluginlib/class_loader.hpp>

#endif  // RACEBOT_PLUGINLIB_CLASS_LOADER_H_

// racebot overlay of pluginlib (upstream_compat/pluginlib): ROS 1's <pluginlib/pluginlib_exceptions.h>, Noetic's name of
// <pluginlib/exceptions.hpp>, which Debian's pluginlib 5.2 has and this one no longer.
#ifndef RACEBOT_PLUGINLIB_PLUGINLIB_EXCEPTIONS_H_
#define RACEBOT_PLUGINLIB_PLUGINLIB_EXCEPTIONS_H_

#include <pluginlib/exceptions.hpp>

#endif  // RACEBOT_PLUGINLIB_PLUGINLIB_EXCEPTIONS_H_

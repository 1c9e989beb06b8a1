// racebot overlay of pluginlib (upstream_compat/pluginlib): ROS 1's <pluginlib/class_loader_imp.h>. As in Noetic,
// the implementation is never included on its own: <pluginlib/class_loader.hpp> brings it.
#ifndef RACEBOT_PLUGINLIB_CLASS_LOADER_IMP_H_
#define RACEBOT_PLUGINLIB_CLASS_LOADER_IMP_H_

#error Header <pluginlib/class_loader_imp.h> is deprecated and never included directly: \
include <pluginlib/class_loader.hpp> instead.

#endif  // RACEBOT_PLUGINLIB_CLASS_LOADER_IMP_H_

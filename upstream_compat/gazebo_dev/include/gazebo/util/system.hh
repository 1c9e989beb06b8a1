// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the visibility macros Gazebo's headers use.
#ifndef GAZEBO_UTIL_SYSTEM_HH_
#define GAZEBO_UTIL_SYSTEM_HH_

#define GZ_PLUGIN_VISIBLE __attribute__((visibility("default")))
#define GZ_COMMON_VISIBLE __attribute__((visibility("default")))
#define GZ_PHYSICS_VISIBLE __attribute__((visibility("default")))
#define GZ_SENSORS_VISIBLE __attribute__((visibility("default")))
#define GZ_RENDERING_VISIBLE __attribute__((visibility("default")))
#define GZ_UTIL_VISIBLE __attribute__((visibility("default")))
#define GAZEBO_VISIBLE __attribute__((visibility("default")))
#define GAZEBO_DEPRECATED(version) __attribute__((deprecated))

#endif

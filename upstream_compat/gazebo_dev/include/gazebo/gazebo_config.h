// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the version Gazebo's config header states.
#ifndef GAZEBO_GAZEBO_CONFIG_H_
#define GAZEBO_GAZEBO_CONFIG_H_

#define GAZEBO_MAJOR_VERSION 11
#define GAZEBO_MINOR_VERSION 14
#define GAZEBO_PATCH_VERSION 0
#define GAZEBO_VERSION "11.14"
#define GAZEBO_VERSION_FULL "11.14.0"
#define GAZEBO_VERSION_NAMESPACE v11
// Not Gazebo: racebot's host of Gazebo plugins (its own physics behind Gazebo's API).
#define GAZEBO_RACEBOT_HOST 1

#endif

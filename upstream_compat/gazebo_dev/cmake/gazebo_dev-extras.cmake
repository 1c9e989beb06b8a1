# As upstream's gazebo_dev: Gazebo's CMake variables become gazebo_dev's, so catkin adds them to the catkin_*
# variables of every package that names gazebo_dev (or gazebo_ros, gazebo_plugins, gazebo_ros_control) as a
# component. Where Gazebo is not installed, find_package(gazebo) finds racebot's stand-in config
# (write_gazebo_config.cmake), which refuses a package that compiles a Gazebo C++ plugin.
find_package(gazebo REQUIRED)
set(gazebo_dev_INCLUDE_DIRS ${GAZEBO_INCLUDE_DIRS})
set(gazebo_dev_LIBRARY_DIRS ${GAZEBO_LIBRARY_DIRS})
set(gazebo_dev_LIBRARIES ${GAZEBO_LIBRARIES})
# Upstream appends Gazebo's flags to CMAKE_CXX_FLAGS of a package that names gazebo_dev. Upstream's gazebo_ros,
# gazebo_plugins and gazebo_ros_control do not hand gazebo_dev on (it is no CATKIN_DEPENDS of theirs); racebot's
# stand-ins do, for the refusal above, so a package that names only them is left as upstream leaves it: its
# CMAKE_CXX_FLAGS untouched (the common `list(APPEND CMAKE_CXX_FLAGS "${CMAKE_CXX_FLAGS} ${GAZEBO_CXX_FLAGS}")`
# puts a ';' into a non-empty one, which breaks the compiler's command line).
list(FIND catkin_FIND_COMPONENTS gazebo_dev _racebot_named)  # not IN_LIST: packages' CMake policies predate it
if(NOT catkin_FIND_COMPONENTS OR NOT _racebot_named EQUAL -1)
  set(CMAKE_CXX_FLAGS "${CMAKE_CXX_FLAGS} ${GAZEBO_CXX_FLAGS}")
endif()

# As upstream's gazebo_dev: Gazebo's CMake variables become gazebo_dev's, so catkin adds them to the catkin_*
# variables of every package that names gazebo_dev (or gazebo_ros, gazebo_plugins, gazebo_ros_control) as a
# component. Where Gazebo is not installed, find_package(gazebo) finds racebot's stand-in config
# (write_gazebo_config.cmake), which refuses a package that compiles a Gazebo C++ plugin.
find_package(gazebo REQUIRED)
set(gazebo_dev_INCLUDE_DIRS ${GAZEBO_INCLUDE_DIRS})
set(gazebo_dev_LIBRARY_DIRS ${GAZEBO_LIBRARY_DIRS})
set(gazebo_dev_LIBRARIES ${GAZEBO_LIBRARIES})
set(CMAKE_CXX_FLAGS "${CMAKE_CXX_FLAGS} ${GAZEBO_CXX_FLAGS}")

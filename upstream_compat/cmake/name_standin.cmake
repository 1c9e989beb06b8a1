# The one pattern of upstream_compat's name stand-ins: packages such as joint_state_controller or
# gazebo_plugins that robot packages name (in launch files, package.xml, find_package(catkin COMPONENTS ...))
# and racebot simulates in Python (racebot_sim_bridge). The stand-in is the package's name, the files upstream
# installs that launch files and tools read (YAML, launch files, plugin description XML: every *.yaml,
# *.launch and *.xml at the package's top, package.xml aside) and a catkin config, so that `rospack find`,
# `$(find pkg)`, `roslaunch pkg file` and `find_package(catkin REQUIRED COMPONENTS pkg)` work as upstream's.
# The config refuses a package whose C++ includes the stand-in's headers (racebot_cpp_check.cmake), or, for a
# stand-in with an include/ folder, headers that folder lacks.
#
# Each stand-in's CMakeLists.txt is:
#
#   cmake_minimum_required(VERSION 3.0.2)
#   project(<name>)
#   include(${CMAKE_CURRENT_SOURCE_DIR}/../cmake/step_aside.cmake)
#   if(NOT RACEBOT_STEP_ASIDE)
#     include(${CMAKE_CURRENT_SOURCE_DIR}/../cmake/name_standin.cmake)
#   endif()
#
# optionally setting, before the include:
#   RACEBOT_STANDIN_DEPENDS  catkin packages its config pulls in, as upstream's CATKIN_DEPENDS does
#                            (gazebo_plugins: gazebo_dev, whose config brings Gazebo's)
#   RACEBOT_STANDIN_HEADERS  the include folders upstream installs (default: the package's name)
#   RACEBOT_STANDIN_EXTRAS   more CFG_EXTRAS, relative to the package's cmake/ folder
#   RACEBOT_STANDIN_CPP_API  ON: the package's include/ holds racebot's copy of part of upstream's C++ API
#   RACEBOT_STANDIN_LIBRARIES  system libraries (absolute paths) its config hands on, as upstream's DEPENDS do

if(NOT RACEBOT_STANDIN_HEADERS)
  set(RACEBOT_STANDIN_HEADERS ${PROJECT_NAME})
endif()

# A stand-in with RACEBOT_STANDIN_CPP_API has racebot's copy of part of upstream's C++ API in its include/ folder
# (ros_control's hardware_interface, controller_interface, realtime_tools: what C++ controllers build against); its
# config hands the folder on and refuses only headers it lacks.
set(_racebot_standin_include)
if(RACEBOT_STANDIN_CPP_API)
  set(_racebot_standin_include include)
  install(DIRECTORY include/ DESTINATION ${CATKIN_GLOBAL_INCLUDE_DESTINATION})
endif()

find_package(catkin REQUIRED COMPONENTS ${RACEBOT_STANDIN_DEPENDS})
catkin_package(
  INCLUDE_DIRS ${_racebot_standin_include}
  LIBRARIES ${RACEBOT_STANDIN_LIBRARIES}
  CATKIN_DEPENDS ${RACEBOT_STANDIN_DEPENDS}
  CFG_EXTRAS
    ${CMAKE_CURRENT_LIST_DIR}/racebot_cpp_check.cmake
    ${CMAKE_CURRENT_LIST_DIR}/standin-extras.cmake
    ${RACEBOT_STANDIN_EXTRAS})

file(GLOB _racebot_standin_files RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}"
  "${CMAKE_CURRENT_SOURCE_DIR}/*.yaml" "${CMAKE_CURRENT_SOURCE_DIR}/*.launch" "${CMAKE_CURRENT_SOURCE_DIR}/*.xml")
list(REMOVE_ITEM _racebot_standin_files package.xml)
if(_racebot_standin_files)
  install(FILES ${_racebot_standin_files} DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
endif()

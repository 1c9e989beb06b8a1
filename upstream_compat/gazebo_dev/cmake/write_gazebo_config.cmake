# Writes racebot's stand-in for Gazebo's own CMake config (gazebo-config.cmake) into this workspace's devel
# space, lib/cmake/gazebo/, where find_package(gazebo) looks (the devel space is on CMAKE_PREFIX_PATH), and
# installs it to the same place. Robot packages call find_package(gazebo REQUIRED) even when they build only
# a plain roscpp node; with this config they build. A package whose code includes Gazebo's C++ headers is
# refused by the config with a message naming it (gazebo-config.cmake.in).
#
# Not written, and an earlier one removed, where a real Gazebo config exists outside this workspace (Ubuntu
# with libgazebo11-dev) or gazebo_dev stepped aside for the real one: ours would come first on the path.

set(_racebot_gazebo_dir "${CATKIN_DEVEL_PREFIX}/lib/cmake/gazebo")

set(_racebot_own)
foreach(_racebot_p "${CATKIN_DEVEL_PREFIX}" "${CMAKE_INSTALL_PREFIX}")
  get_filename_component(_racebot_p "${_racebot_p}" REALPATH)
  list(APPEND _racebot_own "${_racebot_p}")
endforeach()
string(REPLACE ":" ";" _racebot_env_prefixes "$ENV{CMAKE_PREFIX_PATH}")
set(_racebot_real_gazebo "")
foreach(_racebot_prefix ${CMAKE_PREFIX_PATH_AS_IS} ${CMAKE_PREFIX_PATH} ${_racebot_env_prefixes} /usr/local /usr)
  get_filename_component(_racebot_real "${_racebot_prefix}" REALPATH)
  list(FIND _racebot_own "${_racebot_real}" _racebot_index)
  if(NOT _racebot_real_gazebo AND _racebot_index EQUAL -1)
    file(GLOB _racebot_configs
      "${_racebot_prefix}/lib/cmake/gazebo/gazebo-config.cmake"
      "${_racebot_prefix}/lib/*/cmake/gazebo/gazebo-config.cmake"
      "${_racebot_prefix}/lib64/cmake/gazebo/gazebo-config.cmake")
    if(_racebot_configs)
      list(GET _racebot_configs 0 _racebot_real_gazebo)
    endif()
  endif()
endforeach()

if(RACEBOT_STEP_ASIDE OR _racebot_real_gazebo)
  if(_racebot_real_gazebo)
    message(STATUS "gazebo_dev: Gazebo is installed (${_racebot_real_gazebo}); racebot's gazebo config stand-in is not written")
  endif()
  if(EXISTS "${_racebot_gazebo_dir}/racebot_cpp_check.cmake" OR EXISTS "${_racebot_gazebo_dir}/gazebo-config.cmake")
    file(STRINGS "${_racebot_gazebo_dir}/gazebo-config.cmake" _racebot_ours REGEX "racebot's stand-in")
    if(_racebot_ours)
      message(STATUS "gazebo_dev: removing racebot's gazebo config stand-in from ${_racebot_gazebo_dir}")
      file(REMOVE_RECURSE "${_racebot_gazebo_dir}")
    endif()
  endif()
  return()
endif()

# The plugin API's library, libgazebo (Gazebo's own name for its core library), on Debian's ignition-math6 and
# sdformat (12: Gazebo 11 builds on 9, whose ElementPtr API a plugin uses is the same), and the ignition-common
# Gazebo's config hands on with them.
find_package(ignition-math6 REQUIRED)
find_package(sdformat12 REQUIRED)
# ignition-common (4 on Debian 12; Gazebo 11 hands on 3): plugins include its Profiler.hh (IGN_PROFILE)
find_package(ignition-common4 REQUIRED)
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
# CONFIGURE_DEPENDS: a source file added later is built without a fresh configure
file(GLOB _racebot_gazebo_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/../src/*.cc)
add_library(gazebo SHARED ${_racebot_gazebo_sources})
target_include_directories(gazebo PUBLIC ${CMAKE_CURRENT_LIST_DIR}/../include)
target_link_libraries(gazebo PUBLIC ignition-math6::ignition-math6 ${SDFormat_LIBRARIES})
target_compile_options(gazebo PRIVATE -O2)  # as Gazebo's own libraries are built, whatever the build type
set_target_properties(gazebo PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/lib)
install(TARGETS gazebo LIBRARY DESTINATION lib)
# Gazebo's plugin base classes a sensor plugin links by name (target_link_libraries(x ... RayPlugin), found in
# GAZEBO_LIBRARY_DIRS): libRayPlugin, libGpuRayPlugin and libCameraPlugin beside libgazebo.
foreach(_racebot_base RayPlugin GpuRayPlugin CameraPlugin)
  add_library(${_racebot_base} SHARED ${CMAKE_CURRENT_LIST_DIR}/../src/plugins/${_racebot_base}.cc)
  target_link_libraries(${_racebot_base} PUBLIC gazebo)
  target_compile_options(${_racebot_base} PRIVATE -O2)
  set_target_properties(${_racebot_base} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/lib)
  install(TARGETS ${_racebot_base} LIBRARY DESTINATION lib)
endforeach()
install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/../include/gazebo DESTINATION include)

# where they were found, for the config: a package that enables no language (project(x NONE)) has no library
# architecture for find_package to search lib/x86_64-linux-gnu/cmake with
set(RACEBOT_IGNITION_MATH_DIR "${ignition-math6_DIR}")
set(RACEBOT_SDFORMAT_DIR "${sdformat12_DIR}")
set(RACEBOT_IGNITION_COMMON_DIR "${ignition-common4_DIR}")
set(RACEBOT_GAZEBO_VERSION 11.14.0)
get_filename_component(RACEBOT_GAZEBO_INCLUDE "${CMAKE_CURRENT_LIST_DIR}/../include" REALPATH)
set(RACEBOT_GAZEBO_LIBRARY "${CATKIN_DEVEL_PREFIX}/lib/libgazebo.so")
get_filename_component(RACEBOT_CPP_CHECK "${CMAKE_CURRENT_LIST_DIR}/../../cmake/racebot_cpp_check.cmake" REALPATH)
configure_file(${CMAKE_CURRENT_LIST_DIR}/gazebo-config.cmake.in ${_racebot_gazebo_dir}/gazebo-config.cmake @ONLY)
configure_file(${CMAKE_CURRENT_LIST_DIR}/gazebo-config-version.cmake.in
  ${_racebot_gazebo_dir}/gazebo-config-version.cmake @ONLY)
# The installed config finds racebot_cpp_check.cmake beside itself.
set(RACEBOT_CPP_CHECK "\${CMAKE_CURRENT_LIST_DIR}/racebot_cpp_check.cmake")
set(RACEBOT_GAZEBO_INCLUDE "\${CMAKE_CURRENT_LIST_DIR}/../../../include")
set(RACEBOT_GAZEBO_LIBRARY "\${CMAKE_CURRENT_LIST_DIR}/../../libgazebo.so")
configure_file(${CMAKE_CURRENT_LIST_DIR}/gazebo-config.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/installspace/gazebo-config.cmake @ONLY)
install(FILES
  ${CMAKE_CURRENT_BINARY_DIR}/installspace/gazebo-config.cmake
  ${_racebot_gazebo_dir}/gazebo-config-version.cmake
  ${CMAKE_CURRENT_LIST_DIR}/../../cmake/racebot_cpp_check.cmake
  DESTINATION lib/cmake/gazebo)

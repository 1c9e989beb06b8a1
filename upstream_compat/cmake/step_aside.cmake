# Stepping aside for a real upstream package.
#
# Each compatibility package includes this file right after project() and returns at once when
# RACEBOT_STEP_ASIDE is set:
#
#   project(ackermann_msgs)
#   include(${CMAKE_CURRENT_SOURCE_DIR}/../cmake/step_aside.cmake)
#   if(RACEBOT_STEP_ASIDE)
#     return()
#   endif()
#
# A package steps aside when a package of the same name is installed in an underlay, i.e. when
# some prefix other than this workspace's own devel/install space has share/<pkg>/package.xml or
# share/<pkg>/cmake/<pkg>Config.cmake. The prefixes searched are the CMAKE_PREFIX_PATH entries
# (what `source /opt/ros/noetic/setup.bash` or any other setup.bash put there) and /usr (where
# Debian would install one). Stepping aside means:
#   * nothing is generated or installed: no messages, no Python package, no <pkg>Config.cmake,
#     so find_package(), `import <pkg>` and rosmsg all get the underlay's package;
#   * outputs of an earlier build of ours are removed from this devel space (they would come
#     first on every path and shadow the underlay);
#   * a CATKIN_IGNORE file is written next to our package.xml. Without it rospack, roslaunch and
#     catkin_find would still resolve the package name to our source folder (the workspace's
#     source space comes first on ROS_PACKAGE_PATH), so `<node pkg="controller_manager"
#     type="spawner">` would start our script instead of the real one. The file also keeps
#     catkin_make from configuring the package again. Delete it to bring ours back.
# Set -DRACEBOT_COMPAT_FORCE=ON to build ours even when an underlay has the package.
#
# Overlays (upstream_compat/pluginlib, upstream_compat/class_loader) hand on a package Debian has in a later
# generation and add what ROS 1 code includes; they step aside only for the ROS 1 package itself. They set,
# before the include,
#   RACEBOT_STEP_ASIDE_BELOW_VERSION  e.g. 2: an underlay's package counts only when the <version> of its
#                                     package.xml is below it (Noetic's pluginlib 1.13, class_loader 0.5);
#                                     Debian 12's pluginlib 5.2.1 and class_loader 2.4.0 do not, and the
#                                     prefix of the first such package is left in RACEBOT_OVERLAID_PREFIX.
#   RACEBOT_OVERLAY_DEBIAN            TRUE: Debian's own ROS 1 package (in /usr) is overlaid (its prefix left in
#                                     RACEBOT_OVERLAID_PREFIX), any other underlay's (Noetic's /opt/ros/noetic)
#                                     makes ours step aside: for a package Debian has in ROS 1's generation
#                                     but built otherwise (upstream_compat/rosbag_storage)

set(RACEBOT_STEP_ASIDE FALSE)
set(RACEBOT_OVERLAID_PREFIX "")

# In OUT: the <version> of PREFIX/share/<this package>/package.xml, empty when there is none.
function(racebot_underlay_version out prefix)
  set(_version "")
  if(EXISTS "${prefix}/share/${PROJECT_NAME}/package.xml")
    file(STRINGS "${prefix}/share/${PROJECT_NAME}/package.xml" _line REGEX "<version[^>]*>[^<]+</version>"
         LIMIT_COUNT 1)
    string(REGEX REPLACE ".*<version[^>]*>[ \t]*([^< \t]+)[ \t]*</version>.*" "\\1" _version "${_line}")
  endif()
  set(${out} "${_version}" PARENT_SCOPE)
endfunction()

if(RACEBOT_COMPAT_FORCE)
  message(STATUS "${PROJECT_NAME}: RACEBOT_COMPAT_FORCE is set; building ours whatever the underlays have")
  return()
endif()

# Prefixes that are this workspace itself (never a reason to step aside).
set(_racebot_own_prefixes)
foreach(_racebot_p "${CATKIN_DEVEL_PREFIX}" "${CMAKE_INSTALL_PREFIX}" "${CMAKE_BINARY_DIR}/devel")
  if(_racebot_p)
    get_filename_component(_racebot_p "${_racebot_p}" REALPATH)
    list(APPEND _racebot_own_prefixes "${_racebot_p}")
  endif()
endforeach()

# CMAKE_PREFIX_PATH_AS_IS is catkin's copy of the prefix path before it prepended the devel space;
# fall back to the plain variable and the environment for builds outside catkin_make.
set(_racebot_prefixes ${CMAKE_PREFIX_PATH_AS_IS} ${CMAKE_PREFIX_PATH})
if(NOT "$ENV{CMAKE_PREFIX_PATH}" STREQUAL "")
  string(REPLACE ":" ";" _racebot_env_prefixes "$ENV{CMAKE_PREFIX_PATH}")
  list(APPEND _racebot_prefixes ${_racebot_env_prefixes})
endif()
list(APPEND _racebot_prefixes /usr)

set(_racebot_found "")
foreach(_racebot_prefix ${_racebot_prefixes})
  if(_racebot_found OR "${_racebot_prefix}" STREQUAL "")
    continue()
  endif()
  get_filename_component(_racebot_real "${_racebot_prefix}" REALPATH)
  list(FIND _racebot_own_prefixes "${_racebot_real}" _racebot_index)
  if(NOT _racebot_index EQUAL -1)
    continue()
  endif()
  if(EXISTS "${_racebot_prefix}/share/${PROJECT_NAME}/package.xml"
     OR EXISTS "${_racebot_prefix}/share/${PROJECT_NAME}/cmake/${PROJECT_NAME}Config.cmake")
    set(_racebot_found "${_racebot_prefix}")
    if(RACEBOT_OVERLAY_DEBIAN AND _racebot_real STREQUAL "/usr")
      # Debian's own ROS 1 package (it installs to /usr; Noetic's live in /opt/ros/noetic): overlaid, not stepped
      # aside for
      message(STATUS "${PROJECT_NAME}: ${_racebot_prefix} has Debian's ${PROJECT_NAME}; ours overlays it")
      if(NOT RACEBOT_OVERLAID_PREFIX)
        set(RACEBOT_OVERLAID_PREFIX "${_racebot_prefix}")
      endif()
      set(_racebot_found "")
    elseif(RACEBOT_STEP_ASIDE_BELOW_VERSION)
      racebot_underlay_version(_racebot_version "${_racebot_prefix}")
      if(_racebot_version AND NOT _racebot_version VERSION_LESS RACEBOT_STEP_ASIDE_BELOW_VERSION)
        message(STATUS "${PROJECT_NAME}: ${_racebot_prefix} has ${PROJECT_NAME} ${_racebot_version}, a later "
                       "generation than ROS 1's; ours overlays it")
        if(NOT RACEBOT_OVERLAID_PREFIX)
          set(RACEBOT_OVERLAID_PREFIX "${_racebot_prefix}")
        endif()
        set(_racebot_found "")
      endif()
    endif()
  endif()
endforeach()

if(_racebot_found)
  set(RACEBOT_STEP_ASIDE TRUE)
  message(STATUS "${PROJECT_NAME}: using the system package in ${_racebot_found}; ours steps aside")

  # Remove what an earlier build of ours left in this devel space.
  if(CATKIN_DEVEL_PREFIX AND NOT "${CATKIN_DEVEL_PREFIX}" STREQUAL "${_racebot_found}")
    set(_racebot_python_dir "${CATKIN_GLOBAL_PYTHON_DESTINATION}")
    if(NOT _racebot_python_dir)
      set(_racebot_python_dir "${PYTHON_INSTALL_DIR}")
    endif()
    set(_racebot_stale
      "${CATKIN_DEVEL_PREFIX}/share/${PROJECT_NAME}"
      "${CATKIN_DEVEL_PREFIX}/include/${PROJECT_NAME}"
      "${CATKIN_DEVEL_PREFIX}/lib/${PROJECT_NAME}"
      "${CATKIN_DEVEL_PREFIX}/lib/pkgconfig/${PROJECT_NAME}.pc"
      "${CATKIN_DEVEL_PREFIX}/share/common-lisp/ros/${PROJECT_NAME}"
      "${CATKIN_DEVEL_PREFIX}/share/gennodejs/ros/${PROJECT_NAME}"
      "${CATKIN_DEVEL_PREFIX}/share/roseus/ros/${PROJECT_NAME}")
    if(_racebot_python_dir)
      list(APPEND _racebot_stale "${CATKIN_DEVEL_PREFIX}/${_racebot_python_dir}/${PROJECT_NAME}")
    endif()
    foreach(_racebot_path ${_racebot_stale})
      if(EXISTS "${_racebot_path}")
        message(STATUS "${PROJECT_NAME}: removing ${_racebot_path} left by an earlier build of ours")
        file(REMOVE_RECURSE "${_racebot_path}")
      endif()
    endforeach()
  endif()

  # Hide our source folder from rospack/roslaunch/catkin_find (see above).
  if(NOT EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/CATKIN_IGNORE")
    file(WRITE "${CMAKE_CURRENT_SOURCE_DIR}/CATKIN_IGNORE"
      "Written by upstream_compat/cmake/step_aside.cmake: ${PROJECT_NAME} is installed in\n"
      "${_racebot_found}, so racebot's stand-in steps aside. Delete this file to build ours again.\n")
  endif()
endif()

unset(_racebot_found)
unset(_racebot_prefixes)
unset(_racebot_own_prefixes)

# The one pattern of upstream_compat's overlays: a package Debian 12 has, but in its ROS 2 generation (pluginlib
# 5.2, class_loader 2.4), which ROS 1 C++ builds against with headers Debian's lacks (pluginlib/class_loader.h,
# class_loader/class_loader.h, ...). The overlay is a catkin package of the same name whose config hands on
# Debian's package (its include folders and libraries, found here once at build time) behind the overlay's own
# include/ folder, so `find_package(catkin REQUIRED COMPONENTS pluginlib)` and `#include <pluginlib/...>` give a
# ROS 1 package both. It steps aside only for the ROS 1 package itself (step_aside.cmake with
# RACEBOT_STEP_ASIDE_BELOW_VERSION).
#
# Each overlay's CMakeLists.txt is:
#
#   cmake_minimum_required(VERSION 3.0.2)
#   project(<name>)
#   set(RACEBOT_STEP_ASIDE_BELOW_VERSION 2)
#   include(${CMAKE_CURRENT_SOURCE_DIR}/../cmake/step_aside.cmake)
#   if(RACEBOT_STEP_ASIDE)
#     return()
#   endif()
#   find_package(catkin REQUIRED COMPONENTS <the catkin packages its config brings, as upstream's>)
#   include(${CMAKE_CURRENT_SOURCE_DIR}/../cmake/hand_on.cmake)
#   racebot_hand_on()
#   catkin_package(INCLUDE_DIRS include ${RACEBOT_HANDED_ON_INCLUDE_DIRS}
#                  LIBRARIES ${RACEBOT_HANDED_ON_LIBRARIES} CATKIN_DEPENDS ...)
#   install(DIRECTORY include/ DESTINATION ${CATKIN_GLOBAL_INCLUDE_DESTINATION})

# The libraries of LIBRARIES as a link line a catkin config keeps as it is: imported targets resolved to their
# files (and what they link, recursively), plain names to the file found under PREFIX, `-l` flags and absolute
# paths unchanged; a file in PREFIX's library folders becomes `-l<name>`, as Debian's own configs write them, so
# that a library named both ways is named once.
function(racebot_link_line out prefix)
  set(_line)
  foreach(_library ${ARGN})
    if(_library MATCHES "^(debug|optimized|general)$")
      continue()
    elseif(TARGET "${_library}")
      get_target_property(_type "${_library}" TYPE)
      if(NOT _type STREQUAL "INTERFACE_LIBRARY")
        get_target_property(_configurations "${_library}" IMPORTED_CONFIGURATIONS)
        set(_file "")
        foreach(_configuration ${_configurations})
          if(NOT _file)
            get_target_property(_file "${_library}" IMPORTED_LOCATION_${_configuration})
          endif()
        endforeach()
        if(NOT _file)
          get_target_property(_file "${_library}" IMPORTED_LOCATION)
        endif()
        if(_file)
          list(APPEND _line "${_file}")
        endif()
      endif()
      get_target_property(_links "${_library}" INTERFACE_LINK_LIBRARIES)
      if(_links)
        racebot_link_line(_more "${prefix}" ${_links})
        list(APPEND _line ${_more})
      endif()
    elseif(IS_ABSOLUTE "${_library}" OR _library MATCHES "^-")
      list(APPEND _line "${_library}")
    else()
      unset(_file CACHE)
      find_library(_file NAMES "${_library}" PATHS "${prefix}/lib/${CMAKE_LIBRARY_ARCHITECTURE}" "${prefix}/lib"
                   NO_DEFAULT_PATH)
      if(_file)
        list(APPEND _line "${_file}")
      else()
        list(APPEND _line "-l${_library}")
      endif()
      unset(_file CACHE)
    endif()
  endforeach()
  set(_short)
  foreach(_library ${_line})
    if(_library MATCHES "^${prefix}/lib(/${CMAKE_LIBRARY_ARCHITECTURE})?/lib([^/]+)\\.so[.0-9a-z]*$")
      set(_library "-l${CMAKE_MATCH_2}")
    endif()
    list(APPEND _short "${_library}")
  endforeach()
  list(REMOVE_DUPLICATES _short)
  set(${out} ${_short} PARENT_SCOPE)
endfunction()

# Finds the package this overlay hands on (PROJECT_NAME's CMake config in RACEBOT_OVERLAID_PREFIX, which
# step_aside.cmake found) and sets RACEBOT_HANDED_ON_INCLUDE_DIRS and RACEBOT_HANDED_ON_LIBRARIES for
# catkin_package(). Stops the configure, saying what to install, where there is nothing to hand on.
function(racebot_hand_on)
  if(NOT RACEBOT_OVERLAID_PREFIX)
    message(FATAL_ERROR "${PROJECT_NAME}: racebot's overlay hands on an installed ${PROJECT_NAME} and adds "
      "ROS 1's headers, but none is installed (Debian 12: `make setup`, tools/debian-packages.txt; Ubuntu "
      "with ROS Noetic: install ros-noetic-${PROJECT_NAME} and ours steps aside)")
  endif()
  # A config of the same name as the project: found in a function, so that its variables stay here, and
  # without the cache entry, so that packages configured later find this overlay's config, not Debian's.
  # (A cache entry left by an earlier configure, where a later package found this overlay, would be taken as is.)
  unset(${PROJECT_NAME}_DIR CACHE)
  find_package(${PROJECT_NAME} CONFIG QUIET NO_DEFAULT_PATH PATHS "${RACEBOT_OVERLAID_PREFIX}")
  if(NOT ${PROJECT_NAME}_FOUND)
    message(FATAL_ERROR "${PROJECT_NAME}: racebot's overlay hands on the ${PROJECT_NAME} in ${RACEBOT_OVERLAID_PREFIX}, "
      "but its CMake config is not installed there (only its runtime package is?): install its -dev package "
      "(`make setup` does: tools/debian-packages.txt)")
  endif()
  set(_directory "${${PROJECT_NAME}_DIR}")
  unset(${PROJECT_NAME}_DIR CACHE)
  # Its libraries and its imported targets' (an ament config's LIBRARIES may leave out what its target links:
  # class_loader's names only libclass_loader, its target console_bridge and rcpputils too).
  racebot_link_line(_libraries "${RACEBOT_OVERLAID_PREFIX}" ${${PROJECT_NAME}_LIBRARIES} ${${PROJECT_NAME}_TARGETS})
  set(_includes)
  foreach(_include ${${PROJECT_NAME}_INCLUDE_DIRS})
    string(REGEX REPLACE "/+$" "" _include "${_include}")
    list(APPEND _includes "${_include}")
  endforeach()
  list(REMOVE_DUPLICATES _includes)
  message(STATUS "${PROJECT_NAME}: handing on ${_directory}: include ${_includes}; libraries ${_libraries}")
  set(RACEBOT_HANDED_ON_INCLUDE_DIRS ${_includes} PARENT_SCOPE)
  set(RACEBOT_HANDED_ON_LIBRARIES ${_libraries} PARENT_SCOPE)
endfunction()

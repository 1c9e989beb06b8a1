# Refusing, at configure time, a package whose C or C++ code includes headers that only the real upstream
# packages have: racebot's stand-ins (upstream_compat/*) and its gazebo config stand-in have the names, files
# and catkin/CMake configs of those packages but no C++ headers or libraries, since racebot simulates them in
# Python. Without this check such a package would get through CMake and fail deep in the compile with
# "No such file or directory"; with it, catkin_make stops at once naming the package, the file and the line,
# and how to leave the package out.
#
# Included by the catkin config of each name stand-in (upstream_compat/cmake/name_standin.cmake puts it in
# their CFG_EXTRAS) and by the gazebo config that upstream_compat/gazebo_dev writes. It runs in the scope of
# the package that find_package()s them, so CMAKE_CURRENT_SOURCE_DIR is that package's folder.

if(COMMAND racebot_cpp_includes)
  return()
endif()

# The package being configured: the <name> of its package.xml (what CATKIN_BLACKLIST_PACKAGES takes),
# else PROJECT_NAME.
function(racebot_configured_package out)
  set(_name "${PROJECT_NAME}")
  if(EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/package.xml")
    file(STRINGS "${CMAKE_CURRENT_SOURCE_DIR}/package.xml" _line REGEX "<name>[^<]+</name>" LIMIT_COUNT 1)
    if(_line)
      string(REGEX REPLACE ".*<name>[ \t]*([^< \t]+)[ \t]*</name>.*" "\\1" _name "${_line}")
    endif()
  endif()
  set(${out} "${_name}" PARENT_SCOPE)
endfunction()

# In OUT: the first line of the configured package's C/C++ files that includes a header under one of the
# folders in ARGN (`#include <gazebo/gazebo.hh>` is under `gazebo`), as "file: line"; empty when none.
# The package's files are read once per configure run, whatever the number of stand-ins it names.
function(racebot_cpp_includes out)
  set(_key "RACEBOT_CPP_INCLUDES:${CMAKE_CURRENT_SOURCE_DIR}")
  get_property(_scanned GLOBAL PROPERTY "${_key}" SET)
  if(NOT _scanned)
    set(_found "")
    set(_patterns)
    foreach(_ext c cc cpp cxx c++ h hh hpp hxx h++ ipp inl)
      list(APPEND _patterns "${CMAKE_CURRENT_SOURCE_DIR}/*.${_ext}")
    endforeach()
    file(GLOB_RECURSE _files LIST_DIRECTORIES false ${_patterns})
    foreach(_file ${_files})
      if(_file MATCHES "/CMakeFiles/")
        continue()
      endif()
      file(STRINGS "${_file}" _lines REGEX "^[ \t]*#[ \t]*(include[ \t]*[<\"][A-Za-z0-9_]+/|if|elif|else|endif)")
      file(RELATIVE_PATH _relative "${CMAKE_CURRENT_SOURCE_DIR}" "${_file}")
      # An include in a branch Gazebo 11 does not take is not one: `#if (GAZEBO_MAJOR_VERSION < 8)` around
      # <gazebo/math/Vector3.hh> (hector_gazebo_plugins' sensor_model.h). _taken: one 0/1 per open #if, 1 for a
      # condition other than a GAZEBO_MAJOR_VERSION comparison (both branches may be built); _known: k/u.
      set(_taken "")
      set(_known "")
      foreach(_line ${_lines})
        if(_line MATCHES "^[ \t]*#[ \t]*if")
          if(_line MATCHES "^[ \t]*#[ \t]*if[ \t(]+GAZEBO_MAJOR_VERSION[ \t]*(<|<=|>|>=|==|!=)[ \t]*([0-9]+)[ \t)]*(//.*|/\\*.*)?$")
            set(_op "${CMAKE_MATCH_1}")
            set(_n "${CMAKE_MATCH_2}")
            set(_yes 0)
            if((_op STREQUAL "<" AND 11 LESS _n) OR (_op STREQUAL "<=" AND NOT 11 GREATER _n)
               OR (_op STREQUAL ">" AND 11 GREATER _n) OR (_op STREQUAL ">=" AND NOT 11 LESS _n)
               OR (_op STREQUAL "==" AND 11 EQUAL _n) OR (_op STREQUAL "!=" AND NOT 11 EQUAL _n))
              set(_yes 1)
            endif()
            list(APPEND _taken ${_yes})
            list(APPEND _known k)
          else()
            list(APPEND _taken 1)
            list(APPEND _known u)
          endif()
          continue()
        endif()
        list(LENGTH _taken _depth)
        if(_line MATCHES "^[ \t]*#[ \t]*(elif|else|endif)" AND _depth GREATER 0)
          math(EXPR _top "${_depth} - 1")
          list(GET _known ${_top} _kind)
          list(GET _taken ${_top} _was)
          list(REMOVE_AT _taken ${_top})
          list(REMOVE_AT _known ${_top})
          if(CMAKE_MATCH_1 STREQUAL "else")
            if(_kind STREQUAL "k" AND _was EQUAL 1)
              list(APPEND _taken 0)
            else()
              list(APPEND _taken 1)
            endif()
            list(APPEND _known ${_kind})
          elseif(CMAKE_MATCH_1 STREQUAL "elif")  # not evaluated: the branch may be built
            list(APPEND _taken 1)
            list(APPEND _known u)
          endif()
          continue()
        endif()
        list(FIND _taken 0 _skipped)  # (not IN_LIST: packages' cmake_minimum_required(2.8) lack CMP0057)
        if(NOT _line MATCHES "^[ \t]*#[ \t]*include" OR NOT _skipped EQUAL -1)
          continue()
        endif()
        string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([A-Za-z0-9_]+)/.*" "\\1" _folder "${_line}")
        string(REGEX REPLACE "^[ \t]*(#[ \t]*include[ \t]*[<\"][^>\"]*[>\"]).*" "\\1" _include "${_line}")
        list(APPEND _found "${_folder}|${_relative}: ${_include}")
      endforeach()
    endforeach()
    set_property(GLOBAL PROPERTY "${_key}" "${_found}")
  endif()
  get_property(_found GLOBAL PROPERTY "${_key}")
  foreach(_entry ${_found})
    string(FIND "${_entry}" "|" _bar)
    string(SUBSTRING "${_entry}" 0 ${_bar} _folder)
    list(FIND ARGN "${_folder}" _index)
    if(NOT _index EQUAL -1)
      math(EXPR _bar "${_bar} + 1")
      string(SUBSTRING "${_entry}" ${_bar} -1 _where)
      set(${out} "${_where}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

# In OUT: the first line of the configured package's C/C++ files that includes a header under `folder` which is
# not a file under `root` (`#include <gazebo/sensors/RaySensor.hh>` with no root/gazebo/sensors/RaySensor.hh), as
# "file: line"; empty when every such header is there. For a stand-in that has some of upstream's headers.
function(racebot_cpp_unprovided out folder root)
  racebot_cpp_includes(_ignored "${folder}")  # reads the package's files once
  get_property(_found GLOBAL PROPERTY "RACEBOT_CPP_INCLUDES:${CMAKE_CURRENT_SOURCE_DIR}")
  foreach(_entry ${_found})
    string(FIND "${_entry}" "|" _bar)
    string(SUBSTRING "${_entry}" 0 ${_bar} _folder)
    if(NOT _folder STREQUAL folder)
      continue()
    endif()
    string(REGEX REPLACE ".*#[ \t]*include[ \t]*[<\"]([^>\"]*)[>\"].*" "\\1" _header "${_entry}")
    if(NOT EXISTS "${root}/${_header}")
      math(EXPR _bar "${_bar} + 1")
      string(SUBSTRING "${_entry}" ${_bar} -1 _where)
      set(${out} "${_where}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

# The message for a package whose code includes the headers of `standin` at `where` (a racebot_cpp_includes
# result): what is wrong, why, and the catkin_make line that leaves the package out.
function(racebot_cpp_message out standin where)
  racebot_configured_package(_package)
  set(_skip "${_package}")
  if(CATKIN_BLACKLIST_PACKAGES)
    set(_skip "${CATKIN_BLACKLIST_PACKAGES};${_package}")
  endif()
  if(standin STREQUAL "gazebo")
    set(_standin "Gazebo is not installed: find_package(gazebo) finds racebot's stand-in config, which has")
  else()
    set(_standin "Its ${standin} is racebot's stand-in: the package's name, files and catkin config, with")
  endif()
  string(CONCAT _text
    "racebot: package '${_package}' compiles C++ against ${standin} (${where}). racebot simulates Gazebo, "
    "the gazebo_ros plugins and ros_control in Python. ${_standin} no C++ headers or libraries (racebot's "
    "upstream_compat/README.md), so a Gazebo C++ plugin, or a C++ controller or robot hardware, can be neither "
    "built nor loaded here. Leave the package out of the build:\n"
    "  catkin_make -DCATKIN_BLACKLIST_PACKAGES=\"${_skip}\"\n"
    "The plugins and controllers racebot simulates itself are listed in its docs/SUPPORTED.md.")
  set(${out} "${_text}" PARENT_SCOPE)
endfunction()

# FATAL_ERROR when the configured package includes headers under any folder in ARGN (the stand-in `standin`'s).
function(racebot_refuse_cpp standin)
  racebot_cpp_includes(_where ${ARGN})
  if(_where)
    racebot_cpp_message(_message "${standin}" "${_where}")
    message(FATAL_ERROR "${_message}")
  endif()
endfunction()

# FATAL_ERROR when the configured package includes a header under any folder in ARGN that is not a file under
# `root`: for a stand-in (`standin`) that has part of upstream's C++ API.
function(racebot_refuse_unprovided standin root)
  foreach(_folder ${ARGN})
    racebot_cpp_unprovided(_where "${_folder}" "${root}")
    if(_where)
      racebot_configured_package(_package)
      set(_skip "${_package}")
      if(CATKIN_BLACKLIST_PACKAGES)
        set(_skip "${CATKIN_BLACKLIST_PACKAGES};${_package}")
      endif()
      string(CONCAT _text
        "racebot: package '${_package}' includes a header of ${standin} that racebot's copy of its C++ API does "
        "not have (${_where}). Its ${standin} is racebot's stand-in: it has the headers C++ controllers build "
        "against (docs/SUPPORTED.md lists them), not this one. Leave the package out of the build:\n"
        "  catkin_make -DCATKIN_BLACKLIST_PACKAGES=\"${_skip}\"")
      message(FATAL_ERROR "${_text}")
    endif()
  endforeach()
endfunction()

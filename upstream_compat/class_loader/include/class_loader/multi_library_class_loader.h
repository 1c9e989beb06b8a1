// racebot overlay of class_loader (upstream_compat/class_loader): ROS 1's <class_loader/multi_library_class_loader.h>, which Noetic
// keeps as a deprecated name of <class_loader/multi_library_class_loader.hpp> and Debian's class_loader 2.4 no longer has.
#ifndef RACEBOT_CLASS_LOADER_MULTI_LIBRARY_CLASS_LOADER_H_
#define RACEBOT_CLASS_LOADER_MULTI_LIBRARY_CLASS_LOADER_H_

#warning Including header <class_loader/multi_library_class_loader.h> is deprecated, include <class_loader/multi_library_class_loader.hpp> instead.

#include <class_loader/multi_library_class_loader.hpp>

#endif  // RACEBOT_CLASS_LOADER_MULTI_LIBRARY_CLASS_LOADER_H_

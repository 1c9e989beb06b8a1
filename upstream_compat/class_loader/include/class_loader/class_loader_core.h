// racebot overlay of class_loader (upstream_compat/class_loader): ROS 1's <class_loader/class_loader_core.h>, which Noetic
// keeps as a deprecated name of <class_loader/class_loader_core.hpp> and Debian's class_loader 2.4 no longer has.
#ifndef RACEBOT_CLASS_LOADER_CLASS_LOADER_CORE_H_
#define RACEBOT_CLASS_LOADER_CLASS_LOADER_CORE_H_

#warning Including header <class_loader/class_loader_core.h> is deprecated, include <class_loader/class_loader_core.hpp> instead.

#include <class_loader/class_loader_core.hpp>

#endif  // RACEBOT_CLASS_LOADER_CLASS_LOADER_CORE_H_

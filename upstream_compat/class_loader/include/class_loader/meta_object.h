// racebot overlay of class_loader (upstream_compat/class_loader): ROS 1's <class_loader/meta_object.h>, which Noetic
// keeps as a deprecated name of <class_loader/meta_object.hpp> and Debian's class_loader 2.4 no longer has.
#ifndef RACEBOT_CLASS_LOADER_META_OBJECT_H_
#define RACEBOT_CLASS_LOADER_META_OBJECT_H_

#warning Including header <class_loader/meta_object.h> is deprecated, include <class_loader/meta_object.hpp> instead.

#include <class_loader/meta_object.hpp>

#endif  // RACEBOT_CLASS_LOADER_META_OBJECT_H_

// racebot overlay of pluginlib (upstream_compat/pluginlib): ROS 1's <pluginlib/class_list_macros.h>, Noetic's name
// of <pluginlib/class_list_macros.hpp> (PLUGINLIB_EXPORT_CLASS), plus the two macros Kinetic's had and later
// releases dropped, still found in packages built on Noetic.
//
// The class is registered with Debian's class_loader (CLASS_LOADER_REGISTER_CLASS), the registry Debian's
// pluginlib::ClassLoader and nodelet manager load from.
#ifndef RACEBOT_PLUGINLIB_CLASS_LIST_MACROS_H_
#define RACEBOT_PLUGINLIB_CLASS_LIST_MACROS_H_

#include <pluginlib/class_list_macros.hpp>

// PLUGINLIB_DECLARE_CLASS(pkg, class_name, class_type, base_class_type): registers class_type as a plugin of
// base_class_type, as PLUGINLIB_EXPORT_CLASS does (pkg and class_name were never used for the lookup: the
// plugin description XML names the class). Loading it logs a deprecation warning, as Kinetic's did.
#ifndef PLUGINLIB_DECLARE_CLASS
#define PLUGINLIB_DECLARE_CLASS(pkg, class_name, class_type, base_class_type) \
  CLASS_LOADER_REGISTER_CLASS_WITH_MESSAGE(class_type, base_class_type, \
    "pluginlib WARNING: In file " __FILE__ " PLUGINLIB_DECLARE_CLASS is deprecated, " \
    "use PLUGINLIB_EXPORT_CLASS instead.")
#endif

// PLUGINLIB_REGISTER_CLASS(class_name, class_type, base_class_type): the same, for the other old form.
#ifndef PLUGINLIB_REGISTER_CLASS
#define PLUGINLIB_REGISTER_CLASS(class_name, class_type, base_class_type) \
  CLASS_LOADER_REGISTER_CLASS_WITH_MESSAGE(class_type, base_class_type, \
    "pluginlib WARNING: In file " __FILE__ " PLUGINLIB_REGISTER_CLASS is deprecated, " \
    "use PLUGINLIB_EXPORT_CLASS instead.")
#endif

#endif  // RACEBOT_PLUGINLIB_CLASS_LIST_MACROS_H_

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): Gazebo 11's headers bring boost::bind with its global
// placeholders (Boost 1.71's <boost/bind.hpp>), so plugins that include only physics or common headers write
// boost::bind(&X::OnUpdate, this, _1) and build. Debian's Boost 1.74 keeps them global only when asked.
#ifndef GAZEBO_UTIL_BIND_HH_
#define GAZEBO_UTIL_BIND_HH_

#ifndef BOOST_BIND_GLOBAL_PLACEHOLDERS
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#endif
#include <boost/bind.hpp>

#endif

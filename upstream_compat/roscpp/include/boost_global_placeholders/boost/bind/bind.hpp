// racebot overlay of roscpp (upstream_compat/roscpp): Boost's <boost/bind/bind.hpp> with the bind
// placeholders _1 ... _9 declared in the global namespace too.
//
// ROS 1 code writes `boost::bind(&Node::callback, this, _1)` with bare placeholders: on Noetic's platform
// (Ubuntu 20.04, Boost 1.71) <boost/bind/bind.hpp>, which roscpp's headers include, declares them globally.
// Boost 1.73 moved them into boost::placeholders, so with Debian 12's Boost 1.74 the same code stops with
// "'_1' was not declared in this scope". This header is found before Boost's through the include folders of
// roscpp's catkin config (every package that finds roscpp, or nodelet or pluginlib, gets it; GCC drops a -I of
// /usr/include, so it comes first whatever the order), includes Boost's own, and brings the
// placeholders back into the global namespace, as <boost/bind.hpp> still does with BOOST_BIND_GLOBAL_PLACEHOLDERS.
#include_next <boost/bind/bind.hpp>

#ifndef RACEBOT_BOOST_BIND_GLOBAL_PLACEHOLDERS_HPP_
#define RACEBOT_BOOST_BIND_GLOBAL_PLACEHOLDERS_HPP_

#include <boost/version.hpp>

#if BOOST_VERSION >= 107300 && !defined(BOOST_BIND_NO_PLACEHOLDERS)
using namespace boost::placeholders;  // NOLINT(build/namespaces): Boost 1.71's global _1 ... _9
#endif

#endif  // RACEBOT_BOOST_BIND_GLOBAL_PLACEHOLDERS_HPP_

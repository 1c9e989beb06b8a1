// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the message pointer types a subscriber's callback
// takes (`void OnScan(ConstLaserScanStampedPtr &_msg)`), as Gazebo's generated MessageTypes.hh names them.
#ifndef GAZEBO_MSGS_MESSAGETYPES_HH_
#define GAZEBO_MSGS_MESSAGETYPES_HH_

#include <boost/shared_ptr.hpp>

#include "gazebo/msgs/msgs.hh"

namespace gazebo
{
namespace msgs
{
typedef boost::shared_ptr<Time> TimePtr;
typedef boost::shared_ptr<Pose> PosePtr;
typedef boost::shared_ptr<LaserScan> LaserScanPtr;
typedef boost::shared_ptr<LaserScanStamped> LaserScanStampedPtr;
typedef boost::shared_ptr<IMU> IMUPtr;
typedef boost::shared_ptr<Contacts> ContactsPtr;
typedef const boost::shared_ptr<const Time> ConstTimePtr;
typedef const boost::shared_ptr<const Pose> ConstPosePtr;
typedef const boost::shared_ptr<const LaserScan> ConstLaserScanPtr;
typedef const boost::shared_ptr<const LaserScanStamped> ConstLaserScanStampedPtr;
typedef const boost::shared_ptr<const IMU> ConstIMUPtr;
typedef const boost::shared_ptr<const Contacts> ConstContactsPtr;
}  // namespace msgs
// Gazebo's MessageTypes.hh puts the Const...Ptr types in namespace gazebo too
typedef msgs::ConstTimePtr ConstTimePtr;
typedef msgs::ConstPosePtr ConstPosePtr;
typedef msgs::ConstLaserScanPtr ConstLaserScanPtr;
typedef msgs::ConstLaserScanStampedPtr ConstLaserScanStampedPtr;
typedef msgs::ConstIMUPtr ConstIMUPtr;
typedef msgs::ConstContactsPtr ConstContactsPtr;
}  // namespace gazebo

#endif

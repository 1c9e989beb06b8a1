"""twist_mux's node: subscribes to every ~topics entry (geometry_msgs/Twist) and ~locks entry (std_msgs/Bool)
in the node's namespace and relays a Twist to `cmd_vel_out` when mux.has_priority says so. Times are ROS time
(sim time under /use_sim_time), as upstream's ros::Time::now()."""
import threading

import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Bool

from twist_mux.mux import handles, has_priority


class TwistMux:
    def __init__(self):
        try:
            self.topics = handles(rospy.get_param('~topics', None), 'topics')
            self.locks = handles(rospy.get_param('~locks', None), 'locks')
        except ValueError as err:
            rospy.logfatal('Error parsing params: %s' % err)
            self.topics, self.locks = [], []
        self.lock = threading.Lock()
        self.pub = rospy.Publisher('cmd_vel_out', Twist, queue_size=1)
        self.subs = []
        for h in self.topics:
            rospy.loginfo("Topic handler '%s' subscribed to topic '%s': timeout = %s, priority = %d"
                          % (h.name, h.topic, '%gs' % h.timeout if h.timeout else 'None', h.priority))
            self.subs.append(rospy.Subscriber(h.topic, Twist, self._on_twist, h, queue_size=1))
        for h in self.locks:
            rospy.loginfo("Topic handler '%s' subscribed to topic '%s': timeout = %s, priority = %d"
                          % (h.name, h.topic, '%gs' % h.timeout if h.timeout else 'None', h.priority))
            self.subs.append(rospy.Subscriber(h.topic, Bool, self._on_lock, h, queue_size=1))

    def _on_twist(self, msg, handle):
        with self.lock:
            now = rospy.get_time()
            handle.stamp = now
            relay = has_priority(handle, self.topics, self.locks, now)
        if relay:
            self.pub.publish(msg)

    def _on_lock(self, msg, handle):
        with self.lock:
            handle.stamp = rospy.get_time()
            handle.data = bool(msg.data)


def main():
    rospy.init_node('twist_mux')
    TwistMux()
    rospy.spin()

"""The diffbot fixture with gazebo_ros_diff_drive on a PluginWorld: spawned, commanded."""
from geometry_msgs.msg import Twist

from model_plugin_sim import PluginRospy, PluginWorld


class ServiceRospy(PluginRospy):
    """PluginRospy that also records services by name."""

    def __init__(self, params=None):
        super().__init__(params)
        self.services = {}

    def Service(self, name, cls, handler):
        self.services[name] = (cls, handler)
        return self

    def shutdown(self):
        pass


def spawn(tmp_path, urdf, params=None, namespace='/', listen=True):
    """The diffbot; with `listen`, the drive's topics (odometry, tf, joint states) have a subscriber: the drive
    works out only what somebody subscribes to."""
    w = PluginWorld(tmp_path, params)
    w.fake = ServiceRospy(params)
    w.manager.rospy = w.fake
    robot = w.spawn('diffbot', urdf, namespace, (0.0, 0.0, 0.0))
    if listen:
        for topic, pub in w.fake.publishers.items():
            if not topic.endswith('imu'):
                pub.connections = 1
    return w, robot


def command(w, vx, wz, topic='/cmd_vel'):
    msg = Twist()
    msg.linear.x, msg.angular.z = vx, wz
    w.fake.subscribers[topic](msg)

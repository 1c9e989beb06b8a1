"""interactive_marker_twist_server's node `marker_server`: an interactive marker server (topics under
`twist_marker_server/`, as upstream's InteractiveMarkerServer("twist_marker_server")) with one marker at
link_name; each drag publishes a geometry_msgs/Twist on ~cmd_vel and snaps the marker back. The maths is in
twist.py. Needs Debian's python3-interactive-markers and python3-visualization-msgs (tools/debian-packages.txt).
"""
import rospy
from geometry_msgs.msg import Pose, Twist

from interactive_marker_twist_server.twist import controls, settings_from_params, twist


def build_marker(s):
    from visualization_msgs.msg import InteractiveMarker, InteractiveMarkerControl
    marker = InteractiveMarker()
    marker.header.frame_id = s.link_name
    marker.name = s.marker_name
    marker.description = s.description
    marker.scale = s.marker_size_scale
    for name, (w, x, y, z), move in controls(s):
        control = InteractiveMarkerControl()
        control.orientation_mode = InteractiveMarkerControl.FIXED
        control.orientation.w, control.orientation.x = w, x
        control.orientation.y, control.orientation.z = y, z
        control.name = name
        control.interaction_mode = InteractiveMarkerControl.MOVE_AXIS if move else InteractiveMarkerControl.ROTATE_AXIS
        marker.controls.append(control)
    return marker


class MarkerServer:
    def __init__(self):
        from interactive_markers.interactive_marker_server import InteractiveMarkerServer
        self.settings = settings_from_params(lambda name, default: rospy.get_param('~' + name, default))
        self.vel_pub = rospy.Publisher('~cmd_vel', Twist, queue_size=1)
        self.server = InteractiveMarkerServer('twist_marker_server')
        self.server.insert(build_marker(self.settings), self.process_feedback)
        self.server.applyChanges()
        rospy.loginfo('[twist_marker_server] Initialized.')

    def process_feedback(self, feedback):
        p, q = feedback.pose.position, feedback.pose.orientation
        (vx, vy, vz), wz = twist(self.settings, (p.x, p.y, p.z), (q.w, q.x, q.y, q.z))
        vel = Twist()
        vel.linear.x, vel.linear.y, vel.linear.z, vel.angular.z = vx, vy, vz, wz
        self.vel_pub.publish(vel)
        self.server.setPose(self.settings.marker_name, Pose())  # the marker snaps back to the robot
        self.server.applyChanges()


def main():
    rospy.init_node('marker_server')
    try:
        MarkerServer()
    except ImportError as err:
        rospy.logfatal('interactive_marker_twist_server needs Debian\'s python3-interactive-markers and '
                       'python3-visualization-msgs (make setup installs them): %s' % err)
        raise SystemExit(1)
    rospy.spin()

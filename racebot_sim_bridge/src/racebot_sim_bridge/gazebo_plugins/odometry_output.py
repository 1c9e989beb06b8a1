"""What the drive plugins and p3d publish: tf's frame names under a tf_prefix, nav_msgs/Odometry and
the odom -> base transform. tf_resolve is pure; the rest builds messages (imported lazily: the
unit tests of the pure parts need no ROS messages)."""


def tf_resolve(prefix, frame):
    """tf::resolve (tf 1.13): an absolute frame loses its first '/', a relative one goes under the prefix
    (itself without its first '/')."""
    if frame.startswith('/'):
        return frame[1:]
    if prefix:
        return '%s/%s' % (prefix[1:] if prefix.startswith('/') else prefix, frame)
    return frame


def tf_prefix(rospy, namespace, search=True):
    """tf::getPrefixParam(NodeHandle(namespace)): ~tf_prefix searched upwards from `namespace`
    (search=False: only `namespace`/tf_prefix, as p3d's getParam reads it); '' when unset."""
    parts = [p for p in namespace.split('/') if p]
    levels = range(len(parts), -1, -1) if search else (len(parts),)
    for n in levels:
        key = '/' + '/'.join(parts[:n] + ['tf_prefix'])
        try:
            if rospy.has_param(key):
                value = rospy.get_param(key)
                return value if isinstance(value, str) else ''
        except Exception:  # no master reachable: as an unset parameter
            return ''
    return ''


def odometry(stamp, frame_id, child_frame_id, position, orientation, linear, angular, pose_cov, twist_cov):
    from nav_msgs.msg import Odometry
    msg = Odometry()
    msg.header.stamp = stamp
    msg.header.frame_id = frame_id
    msg.child_frame_id = child_frame_id
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    p.x, p.y, p.z = position
    q.x, q.y, q.z, q.w = orientation
    msg.pose.covariance = list(pose_cov)
    t = msg.twist.twist
    t.linear.x, t.linear.y, t.linear.z = linear
    t.angular.x, t.angular.y, t.angular.z = angular
    msg.twist.covariance = list(twist_cov)
    return msg


def transform(stamp, frame_id, child_frame_id, position, orientation):
    """A tf2_msgs/TFMessage with one transform."""
    from geometry_msgs.msg import TransformStamped
    from tf2_msgs.msg import TFMessage
    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id = frame_id
    t.child_frame_id = child_frame_id
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = position
    r = t.transform.rotation
    r.x, r.y, r.z, r.w = orientation
    return TFMessage(transforms=[t])

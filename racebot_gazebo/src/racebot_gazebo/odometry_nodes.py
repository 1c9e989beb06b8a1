"""The two odometry nodes: ground truth from the simulator, and wheel odometry from the joints.

Frames follow REP 105: `odom` is the parent of `base_footprint`, and exactly one node may
publish that transform. gazebo_odometry publishes it by default; wheel_odometry publishes its
estimate as a message only, unless told to take over the transform (then switch the other's off).

gazebo_odometry (GroundTruthOdometry), as the racecar project's gazebo_odometry.py:
  subscribes /gazebo/link_states (gazebo_msgs/LinkStates)
  publishes  odom (nav_msgs/Odometry; the world pose of the link, its twist in the child frame)
             and tf frame_id -> child_frame_id
  ~link_name      (str, racebot::base_footprint)  the entry of link_states to report
  ~frame_id       (str, odom)
  ~child_frame_id (str, base_footprint)
  ~rate           (Hz, 20)    this often, in sim time (odometry.SimTimeTicks; 0: every link_states)
  ~publish_tf     (bool, true)

wheel_odometry (WheelOdometry): integrates the rear wheel speeds and steering hinge angles
(odometry.WheelSpeedOdometry) from every joint_states message.
  subscribes joint_states (sensor_msgs/JointState; remap to /racebot/joint_states)
  publishes  wheel_odom (nav_msgs/Odometry), tf frame_id -> child_frame_id only if ~publish_tf
  ~wheel_radius (m, 0.032), ~wheelbase (m, 0.26), ~rear_axle_x (m, -0.13: the rear axle's x in
  the child frame), ~rear_wheel_joints ([left_rear_wheel_joint, right_rear_wheel_joint]),
  ~steering_joints ([left_steering_hinge_joint, right_steering_hinge_joint]),
  ~frame_id (odom), ~child_frame_id (base_footprint), ~publish_tf (bool, false)
"""
import threading

import rospy
import tf2_ros
from gazebo_msgs.msg import LinkStates
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState

from racebot_gazebo import odometry
from racebot_gazebo.odometry import rotate_back, yaw_quaternion

# Diagonal covariances (x, y, z, roll, pitch, yaw): ground truth is exact; the wheel estimate
# drifts with slip (a few percent of the distance driven).
GROUND_TRUTH_VARIANCE = 1e-9
WHEEL_POSE_VARIANCE = (1e-3, 1e-3, 1e6, 1e6, 1e6, 1e-2)
WHEEL_TWIST_VARIANCE = (1e-3, 1e-3, 1e6, 1e6, 1e6, 1e-2)


def diagonal(values):
    cov = [0.0] * 36
    for i, v in enumerate(values):
        cov[7 * i] = v
    return cov


def transform(odom):
    t = TransformStamped()
    t.header = odom.header
    t.child_frame_id = odom.child_frame_id
    p = odom.pose.pose.position
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = p.x, p.y, p.z
    t.transform.rotation = odom.pose.pose.orientation
    return t


def publish_unless_closing(pub, tf, odom):
    """odom on `pub`, and its transform on `tf` (None: none), unless rospy is shutting down: a callback that
    runs while rospy closes its topics meets ROSException('publish() to a closed topic'), and rospy logs it as a
    bad callback with a traceback (odometry.test's log, 2026-12-03); roscpp's publish does nothing then."""
    try:
        pub.publish(odom)
        if tf is not None:
            tf.sendTransform(transform(odom))
    except rospy.ROSException:
        if not (rospy.is_shutdown() or rospy.core.is_shutdown_requested()):
            raise


def _frame(name, default):
    return str(rospy.get_param(name, default)).strip().lstrip('/') or default


class GroundTruthOdometry:
    def __init__(self):
        self.link_name = rospy.get_param('~link_name', 'racebot::base_footprint')
        self.frame_id = _frame('~frame_id', 'odom')
        self.child_frame_id = _frame('~child_frame_id', 'base_footprint')
        self.ticks = odometry.SimTimeTicks(float(rospy.get_param('~rate', 20.0)))
        self.tf = tf2_ros.TransformBroadcaster() if rospy.get_param('~publish_tf', True) else None
        self.pub = rospy.Publisher('odom', Odometry, queue_size=10)
        self.missing_warned = False
        self.sub = rospy.Subscriber('/gazebo/link_states', LinkStates, self.on_link_states, queue_size=1)

    def on_link_states(self, msg):
        now = rospy.Time.now()
        if not self.ticks.due(now.to_sec()):
            return
        try:
            i = msg.name.index(self.link_name)
        except ValueError:
            if not self.missing_warned:
                rospy.logwarn('gazebo_odometry: no link %r in /gazebo/link_states yet (links: %s)'
                              % (self.link_name, ', '.join(msg.name[:12])))
                self.missing_warned = True
            return
        pose, twist = msg.pose[i], msg.twist[i]
        q = (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
        odom = Odometry()
        odom.header.stamp = now
        odom.header.frame_id = self.frame_id
        odom.child_frame_id = self.child_frame_id
        odom.pose.pose = pose
        odom.pose.covariance = diagonal([GROUND_TRUTH_VARIANCE] * 6)
        lin = rotate_back(q, (twist.linear.x, twist.linear.y, twist.linear.z))  # world -> body axes
        ang = rotate_back(q, (twist.angular.x, twist.angular.y, twist.angular.z))
        odom.twist.twist.linear.x, odom.twist.twist.linear.y, odom.twist.twist.linear.z = lin
        odom.twist.twist.angular.x, odom.twist.twist.angular.y, odom.twist.twist.angular.z = ang
        odom.twist.covariance = diagonal([GROUND_TRUTH_VARIANCE] * 6)
        publish_unless_closing(self.pub, self.tf, odom)


class WheelOdometry:
    def __init__(self):
        self.model = odometry.WheelSpeedOdometry(float(rospy.get_param('~wheel_radius', odometry.WHEEL_RADIUS)),
                                                 float(rospy.get_param('~wheelbase', odometry.WHEELBASE)),
                                                 float(rospy.get_param('~rear_axle_x', odometry.REAR_AXLE_X)))
        self.rear = list(rospy.get_param('~rear_wheel_joints', list(odometry.REAR_WHEEL_JOINTS)))
        self.steering = list(rospy.get_param('~steering_joints', list(odometry.STEERING_JOINTS)))
        if not self.rear or not self.steering:
            raise ValueError('~rear_wheel_joints and ~steering_joints must name at least one joint each')
        self.frame_id = _frame('~frame_id', 'odom')
        self.child_frame_id = _frame('~child_frame_id', 'base_footprint')
        self.tf = tf2_ros.TransformBroadcaster() if rospy.get_param('~publish_tf', False) else None
        self.lock = threading.Lock()
        self.pub = rospy.Publisher('wheel_odom', Odometry, queue_size=10)
        self.previous_positions = None
        self.missing_warned = False
        self.sub = rospy.Subscriber('joint_states', JointState, self.on_joint_states, queue_size=50)

    def _read(self, msg):
        """(stamp, rear wheel speeds, steering angles) of a JointState, or None if joints are missing."""
        index = {n: i for i, n in enumerate(msg.name)}
        if any(j not in index for j in self.rear + self.steering):
            if not self.missing_warned:
                rospy.logwarn('wheel_odometry: joint_states lacks some of %s' % (self.rear + self.steering))
                self.missing_warned = True
            return None
        stamp = msg.header.stamp if not msg.header.stamp.is_zero() else rospy.Time.now()
        t = stamp.to_sec()
        positions = [msg.position[index[j]] for j in self.rear]
        if len(msg.velocity) == len(msg.name):
            speeds = [msg.velocity[index[j]] for j in self.rear]
        elif self.previous_positions is not None and t > self.previous_positions[0]:  # differentiate
            t0, p0 = self.previous_positions
            speeds = [(p - q) / (t - t0) for p, q in zip(positions, p0)]
        else:
            speeds = [0.0] * len(self.rear)
        self.previous_positions = (t, positions)
        return stamp, speeds, [msg.position[index[j]] for j in self.steering]

    def on_joint_states(self, msg):
        with self.lock:
            sample = self._read(msg)
            if sample is None:
                return
            stamp, speeds, angles = sample
            t = stamp.to_sec()
            if self.model.last is not None and t < self.model.last[0]:
                self.model.reset()  # simulation reset: start over where the car starts over
            self.model.update(t, speeds, angles)
            x, y, yaw = self.model.pose
            vx, vy, wz = self.model.twist
        odom = Odometry()
        odom.header.stamp = stamp
        odom.header.frame_id = self.frame_id
        odom.child_frame_id = self.child_frame_id
        odom.pose.pose.position.x, odom.pose.pose.position.y = x, y
        q = yaw_quaternion(yaw)
        o = odom.pose.pose.orientation
        o.x, o.y, o.z, o.w = q
        odom.pose.covariance = diagonal(WHEEL_POSE_VARIANCE)
        odom.twist.twist.linear.x, odom.twist.twist.linear.y, odom.twist.twist.angular.z = vx, vy, wz
        odom.twist.covariance = diagonal(WHEEL_TWIST_VARIANCE)
        publish_unless_closing(self.pub, self.tf, odom)


def main_ground_truth():
    rospy.init_node('gazebo_odometry')
    GroundTruthOdometry()
    rospy.spin()


def main_wheel():
    rospy.init_node('wheel_odometry')
    try:
        WheelOdometry()
    except ValueError as err:
        rospy.logfatal('wheel_odometry: %s' % err)
        raise SystemExit(1)
    rospy.spin()

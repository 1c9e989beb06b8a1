"""libgazebo_ros_hand_of_god.so (gazebo_plugins noetic-devel): a link pulled to a tf frame by a spring-damper.

Parameters: linkName (required), frameId (hog), kl (200), ka (200); robotNamespace is read and not used, as
upstream (its tf frames are global). Load turns the link's gravity off and sets the damping for critical damping,
cl = 2 sqrt(kl m), ca = 2 sqrt(ka Ixx) (the link's mass and the first diagonal entry of its inertia). Every world
update it looks up world -> <frameId>_desired (the latest, in its own tf buffer fed by /tf and /tf_static; an
error is logged once until a lookup works again) and adds, as upstream computes them (hand_of_god_wrench):
  force  = kl (p_desired - p) - cl v                      at the centre of mass, world axes (Link::AddForce)
  torque = ka log(q^-1 q_desired).xyz - ca w_link         in the link's axes (Link::AddRelativeTorque)
where p, q are the link frame's pose, v its origin's velocity, w_link its angular velocity in its own axes and
log the quaternion logarithm (half the rotation vector: upstream's). Then it sends world -> <frameId>_actual,
the link's pose, stamped with the sim time.
PyBullet has no per-link gravity switch: the link's weight is cancelled by an equal upward force at its centre
of mass every step, the same thing on that link (f3d does not count it, as Gazebo adds no force).
"""
import math

from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_plugins.odometry_output import transform
from racebot_sim_bridge.kinematics.rotations import matrix, rotate, rotate_back

LOG_EPSILON = 1e-3  # ignition::math::Quaternion::Log's "sin(A) near zero"


def rotation_of(m):
    """ignition::math::Matrix4::Rotation: the quaternion (x, y, z, w) of a 3 x 3 rotation matrix (rows), by
    Shoemake's method (w >= 0 when the trace is positive)."""
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        root = math.sqrt(trace + 1.0)
        w = root / 2.0
        root = 1.0 / (2.0 * root)
        return ((m[2][1] - m[1][2]) * root, (m[0][2] - m[2][0]) * root, (m[1][0] - m[0][1]) * root, w)
    i = 0
    if m[1][1] > m[0][0]:
        i = 1
    if m[2][2] > m[i][i]:
        i = 2
    j, k = (i + 1) % 3, (i + 2) % 3
    root = math.sqrt(m[i][i] - m[j][j] - m[k][k] + 1.0)
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = root / 2.0
    root = 1.0 / (2.0 * root)
    q[j] = (m[j][i] + m[i][j]) * root
    q[k] = (m[k][i] + m[i][k]) * root
    q[3] = (m[k][j] - m[j][k]) * root
    return tuple(q)


def quaternion_log(q):
    """ignition::math::Quaternion::Log's vector part: angle/sin(angle) * (x, y, z), angle = acos(w)."""
    x, y, z, w = q
    if abs(w) < 1.0:
        angle = math.acos(w)
        s = math.sin(angle)
        if abs(s) >= LOG_EPSILON:
            c = angle / s
            return c * x, c * y, c * z
    return x, y, z


def hand_of_god_wrench(position, orientation, linear, angular, desired_position, desired_orientation, kl, ka, cl,
                       ca):
    """(force in world axes, torque in the link's axes) upstream adds; `linear`, `angular` in world axes."""
    r = matrix(orientation)
    rt = tuple(tuple(r[c][row] for c in range(3)) for row in range(3))  # R^-1 = R^T
    d = matrix(desired_orientation)
    error = rotation_of(tuple(tuple(sum(rt[a][n] * d[n][b] for n in range(3)) for b in range(3)) for a in range(3)))
    log = quaternion_log(error)
    relative_angular = rotate_back(orientation, angular)
    force = tuple(kl * (desired_position[i] - position[i]) - cl * linear[i] for i in range(3))
    torque = tuple(ka * log[i] - ca * relative_angular[i] for i in range(3))
    return force, torque


class HandOfGod(ModelPlugin):
    libraries = ('libgazebo_ros_hand_of_god.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        if not p.has('linkName'):
            raise PluginError('<linkName> is missing: give the link to pull to the tf frame <frameId>_desired')
        self.link = self.link_param('linkName', 'the link to pull to the tf frame')
        self.frame_id = p.string('frameId', 'hog')
        self.kl = p.number('kl', 200.0, minimum=0)  # negative: upstream's sqrt gives NaN forces
        self.ka = p.number('ka', 200.0, minimum=0)
        self.index = robot.body.link_index[self.link]
        dynamics = robot.body.links[self.link].dynamics()
        self.cl = 2.0 * math.sqrt(self.kl * dynamics.mass)
        self.ca = 2.0 * math.sqrt(self.ka * dynamics.inertia_diagonal[0])
        self.weight = tuple(-dynamics.mass * g for g in self.world.gravity)  # SetGravityMode(false)'s stand-in
        import tf2_ros
        from tf2_msgs.msg import TFMessage
        self.tf2 = tf2_ros
        self.buffer = tf2_ros.Buffer(debug=False)
        self.subscriber('/tf', TFMessage, self._on_tf, queue_size=100)
        self.subscriber('/tf_static', TFMessage, self._on_tf_static, queue_size=100)
        self.tf_pub = ctx.tf_publisher()
        self.errored = False
        self.last_time = ctx.sim.time

    def _on_tf(self, msg):
        for t in msg.transforms:
            self.buffer.set_transform(t, 'default_authority')

    def _on_tf_static(self, msg):
        for t in msg.transforms:
            self.buffer.set_transform_static(t, 'default_authority')

    def before_physics(self, time):
        if time < self.last_time:  # reset_simulation: tf's listener clears its buffer on a jump back in time
            self.buffer.clear()
        self.last_time = time
        link = self.robot.body.links[self.link]
        link.apply_wrench(self.weight, (0.0, 0.0, 0.0), accumulate=False)
        try:
            desired = self.buffer.lookup_transform('world', self.frame_id + '_desired', self.ctx.rospy.Time(0))
        except self.tf2.TransformException as err:
            if not self.errored:
                self.ctx.rospy.logerr('%s: %s' % (self.label, err))
                self.errored = True
            return
        self.errored = False
        t, r = desired.transform.translation, desired.transform.rotation
        position, orientation, linear, angular = link_motion(self.world, self.robot.body, self.link)
        force, torque = hand_of_god_wrench(position, orientation, linear, angular, (t.x, t.y, t.z),
                                           (r.x, r.y, r.z, r.w), self.kl, self.ka, self.cl, self.ca)
        link.apply_wrench(force, rotate(orientation, torque))
        msg = transform(self.stamp(time), 'world', self.frame_id + '_actual', position, orientation)
        self.tf_pub.publish(msg)

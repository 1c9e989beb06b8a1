"""libgazebo_ros_harness.so (gazebo_plugins noetic-devel, on Gazebo 11's HarnessPlugin): the model hung from the world
by the plugin's own <joint>s, a winch on one of them, and a detach.

As HarnessPlugin::Load/Attach: every <joint name type> in the plugin block is made (parent `world`, child a link of
the model; <pose> in the child link's frame; <axis><xyz>, in that joint frame unless <use_parent_model_frame>;
<axis><dynamics><damping>; <axis><limit><effort>, which truncates the winch force when >= 0, Joint::SetForce); none
made refuses the plugin ("No joints specified in the harness plugin"). <detach> and <winch><joint> name one of them
(an unknown name: the first joint, with upstream's warning); Gazebo 11 leaves either unset when its element is
missing (its warning says the first joint, yet it stays unset), and an update without a winch detaches at once.
<winch><pos_pid> and <vel_pid>: p, i, d, i_max, i_min, cmd_max, cmd_min (each 0 when absent: a PID without cmd_max
is clamped to 0, as upstream), Gazebo's common::PID (gazebo_pid.py). Every world update, while attached: with a
target velocity 0 the position PID holds the position the winch had when 0 was set; the velocity PID's force, never
negative (it only lifts), plus the position PID's, plus -damping * velocity, pushes the winch joint.
ROS (GazeboRosHarness): std_msgs/Float32 on /<model>/harness/velocity sets the winch velocity (0: hold here);
std_msgs/Bool true on /<model>/harness/detach takes the detach joint away and stops the updates, for good.

In PyBullet a harness joint is a constraint between the link and the world: prismatic (a slider: the link keeps its
orientation and slides along the axis), fixed, or ball (a point); the winch pushes the link along the axis. Not
simulated: the joint's <limit> lower/upper (the link slides past them; the winch's position hold is what keeps it),
other joint types (refused with a warning), a parent other than the world, Gazebo 11's ~/<model>/harness/attach.
"""
import math
import xml.etree.ElementTree as ET

from racebot_sim_bridge.engine import world_constraints
from racebot_sim_bridge.gazebo_plugins.gazebo_pid import GazeboPid
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.kinematics.rotations import compose, rotate


def _number(elem, path, default):
    text = elem.findtext(path) if elem is not None else None
    try:
        value = float(text)
    except (TypeError, ValueError):
        return default
    return value if math.isfinite(value) else default


def gazebo_pid(elem):
    """A <pos_pid> or <vel_pid> as HarnessPlugin reads it (every value 0 when absent)."""
    return GazeboPid(*(_number(elem, tag, 0.0) for tag in ('p', 'i', 'd', 'i_max', 'i_min', 'cmd_max', 'cmd_min')))


class HarnessJoint:
    """One harness joint on the PyBullet body: its constraint, its anchor and axis in the world at attach."""

    def __init__(self, plugin, elem):
        self.name = elem.get('name') or ''
        self.type = elem.get('type') or ''
        self.world = plugin.world
        body = plugin.robot.body
        parent, child = (elem.findtext(tag, '').strip() for tag in ('parent', 'child'))
        if self.type not in world_constraints.KINDS:
            raise ValueError("type '%s' is not simulated (prismatic, fixed and ball are)" % self.type)
        if parent != 'world':
            raise ValueError("parent '%s': only a joint to the world is simulated" % parent)
        prefix = plugin.robot.name + '::'
        self.link = plugin.link_param('child', 'the harnessed link', name=child[len(prefix):]
                                      if child.startswith(prefix) else child)
        self.index = body.link_index[self.link]
        pose = tuple(float(v) for v in (elem.findtext('pose') or '0 0 0 0 0 0').split())
        axis = tuple(float(v) for v in (elem.findtext('axis/xyz') or '0 0 1').split())
        norm = math.sqrt(sum(a * a for a in axis)) or 1.0
        axis = tuple(a / norm for a in axis)
        frame, _ = body.links[self.link].state()
        frame = (frame.position, frame.orientation)
        self.anchor = tuple(pose[:3])  # in the link frame
        joint_frame = compose(frame, pose)
        if (elem.findtext('axis/use_parent_model_frame') or '').strip().lower() in ('true', '1'):
            self.axis = rotate(body.frame_pose().orientation, axis)
        else:
            self.axis = rotate(joint_frame[1], axis)
        self.start = joint_frame[0]
        self.damping = _number(elem, 'axis/dynamics/damping', 0.0)
        self.effort = _number(elem, 'axis/limit/effort', -1.0)
        self.constraint = world_constraints.hold(self.world.client, body.id, self.index, self.type, frame,
                                                 self.start, self.axis)

    def anchor_state(self, body):
        """(position along the axis since attach, velocity along it) of the anchor."""
        frame, twist = body.links[self.link].state()
        anchor = compose((frame.position, frame.orientation), (self.anchor, (0.0, 0.0, 0.0, 1.0)))[0]
        com = body.links[self.link].com_position()
        w = twist.angular
        r = [a - c for a, c in zip(anchor, com)]
        velocity = [twist.linear[0] + w[1] * r[2] - w[2] * r[1], twist.linear[1] + w[2] * r[0] - w[0] * r[2],
                    twist.linear[2] + w[0] * r[1] - w[1] * r[0]]
        return (sum((a - s) * x for a, s, x in zip(anchor, self.start, self.axis)),
                sum(v * x for v, x in zip(velocity, self.axis)))


class Harness(ModelPlugin):
    libraries = ('libgazebo_ros_harness.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        elem = spec.element if spec.element is not None else ET.Element('plugin')
        self.joints = []
        for joint in elem.findall('joint'):
            try:
                self.joints.append(HarnessJoint(self, joint))
            except (ValueError, PluginError) as err:
                self.ctx.rospy.logerr('%s: Unable to load joint[%s]. %s' % (self.label, joint.get('name'), err))
        if not self.joints:
            raise PluginError('No joints specified in the harness plugin.The harness plugin will not run')
        names = [j.name for j in self.joints]
        self.detach_index = self.winch_index = -1
        if elem.find('detach') is not None:
            self.detach_index = self._index(names, elem.findtext('detach').strip(), 'Invalid <detach> joint name[%s] '
                                            'in the harness plugin. The first joint will be used as the detach joint.')
        else:
            self.warn('A <detach> element is missing from the harness plugin. The first joint will be used as the '
                      'detach joint.')
        winch = elem.find('winch')
        if winch is None:
            self.warn('A <winch> element is missing from the harness plugin. The first joint will be used as the '
                      'winch.')
        elif winch.find('joint') is None:
            self.warn('A <winch><joint>joint_name</joint></winch> element is missing from the harness plugin. The '
                      'first joint will be used as the winch.')
        else:
            self.winch_index = self._index(names, winch.findtext('joint').strip(), 'Invalid <joint> name[%s] in the '
                                           '<winch> element of the harness plugin. The first joint will be used as '
                                           'the winch.')
        self.pos_pid = gazebo_pid(winch.find('pos_pid') if winch is not None else None)
        self.vel_pid = gazebo_pid(winch.find('vel_pid') if winch is not None else None)
        self.target_velocity = self.target_position = 0.0
        self.prev_time = None
        self.velocity_command = self.detach_command = None  # set by the subscribers, taken by the physics thread
        self.attached = True
        from std_msgs.msg import Bool, Float32
        self.subscriber('/%s/harness/velocity' % robot.name, Float32, self.on_velocity)
        self.subscriber('/%s/harness/detach' % robot.name, Bool, self.on_detach)

    def _index(self, names, name, warning):
        if name in names:
            return names.index(name)
        self.warn(warning % name)
        return 0

    def on_velocity(self, msg):
        self.velocity_command = msg.data

    def on_detach(self, msg):
        if msg.data:
            self.detach_command = True

    def before_physics(self, time):
        if not self.attached:
            return
        if self.detach_command:
            self.detach()
            return
        body = self.robot.body
        velocity, self.velocity_command = self.velocity_command, None
        if velocity is not None:
            self.set_winch_velocity(velocity)
        if self.prev_time is None:  # bootstrap the time
            self.prev_time = time
            return
        dt = time - self.prev_time
        if not 0 <= self.winch_index < len(self.joints):
            if 0 <= self.detach_index < len(self.joints):
                self.info('Detaching harness joint')
                self.detach()
            return
        winch = self.joints[self.winch_index]
        position, speed = winch.anchor_state(body)
        p_error = position - self.target_position if abs(self.target_velocity) <= 1e-6 else 0.0
        force = self.pos_pid.update(p_error, dt) + max(self.vel_pid.update(speed - self.target_velocity, dt), 0.0)
        if winch.effort >= 0:
            force = min(max(force, -winch.effort), winch.effort)
        force -= winch.damping * speed
        body.links[winch.link].apply_wrench(tuple(force * a for a in winch.axis), (0.0, 0.0, 0.0), accumulate=False)
        self.prev_time = time

    def set_winch_velocity(self, value):
        if not 0 <= self.winch_index < len(self.joints):
            self.ctx.rospy.logerr('%s: No known winch joint to set velocity' % self.label)
            return
        self.target_velocity = value
        if abs(value) <= 1e-6:  # hold here
            self.target_position = self.joints[self.winch_index].anchor_state(self.robot.body)[0]
            self.pos_pid.reset()

    def detach(self):
        self.detach_command = None
        if not 0 <= self.detach_index < len(self.joints):
            self.ctx.rospy.logerr('%s: No known joint to detach' % self.label)
            return
        world_constraints.release(self.world.client, self.joints[self.detach_index].constraint)
        self.joints = []
        self.detach_index = self.winch_index = -1
        self.attached = False

    def close(self):
        for joint in self.joints:
            if self.robot.name in self.world.bodies:
                world_constraints.release(self.world.client, joint.constraint)
        self.joints = []
        super().close()


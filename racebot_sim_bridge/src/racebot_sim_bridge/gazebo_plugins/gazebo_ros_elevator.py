"""libgazebo_ros_elevator.so (gazebo_plugins noetic-devel, on Gazebo 11's ElevatorPlugin): a lift and its door.

Parameters: lift_joint and door_joint (required: a joint of the model, plain or scoped `model::joint`; else
refused, as the ElevatorPlugin disables itself), floor_height (3 m, with upstream's warning when absent),
door_wait_time (5 s), topic (`elevator`), robotNamespace (text + '/'). A std_msgs/String on the topic holding a
floor number (std::stoi: leading blanks, a sign, the digits; what follows is ignored) starts upstream's sequence
unless one is under way (then the message is dropped): close the door, move to the floor, open the door, wait
door_wait_time, close the door. Every world update both controllers push their joints with Gazebo's common::PID
(gazebo_pid.py) as a joint force, clamped to the joint's effort limit (Joint::SetForce):
- the lift, PID(100000, 0, 100000) on position - floor * floor_height; at the floor when within 0.15 m;
- the door, PID(2, 0, 1) on position - (1 open, 0 closed); done when within 0.05. Its dt is the time since its
  first update (upstream never moves its prevSimTime on), which leaves its d-term nearly nothing, as upstream.
Reset (reset_world) drops the sequence and restarts the controllers' clocks; the floor and door targets stay.
Differences: the wait is counted in sim time (Gazebo's common::Timer counts wall time: the same at real-time
speed); a message that is no number is logged (upstream's std::stoi throws in the ROS callback thread).
"""
import re

from racebot_sim_bridge.gazebo_plugins.gazebo_pid import GazeboPid
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in

OPEN, CLOSE = 1.0, 0.0  # the door's targets (DoorController::Target), metres along its joint
_STOI = re.compile(r'\s*([+-]?\d+)')


def scoped_joint(plugin, tag):
    """The movable joint <tag> names, as Model::GetJoint finds it: its plain name or `<model>::<name>`."""
    name = plugin.params.string(tag, '')
    prefix = plugin.robot.name + '::'
    plain = name[len(prefix):] if name.startswith(prefix) else name
    joint = plugin.robot.body.joints.get(plain)
    if joint is None:
        raise PluginError('Unable to find %s[%s] (the movable joints: %s); the plugin is disabled'
                          % (tag.replace('_', ' '), name, ', '.join(sorted(plugin.robot.body.joints)) or 'none'))
    return joint


def push(plugin, joint, force):
    """Joint::SetForce for one update: the force clamped to the joint's effort limit (none when 0)."""
    if joint.max_effort > 0:
        force = min(max(force, -joint.max_effort), joint.max_effort)
    joint.apply_effort(force)


class Elevator(ModelPlugin):
    libraries = ('libgazebo_ros_elevator.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.door_wait_time = p.number('door_wait_time', 5.0)
        if not p.has('floor_height'):
            self.warn('No <floor_height> specified for elevator plugin. Using a height of 3 meters. This value may '
                      'cause the elevator to move incorrectly.')
        self.floor_height = p.number('floor_height', 3.0)
        self.lift = scoped_joint(self, 'lift_joint')
        self.door = scoped_joint(self, 'door_joint')
        self.floor, self.door_target = 0, CLOSE
        self.lift_pid, self.door_pid = GazeboPid(100000, 0, 100000), GazeboPid(2, 0, 1.0)
        self.states = []  # [[kind, argument, started]]: upstream's state queue
        self.requested = None  # the floor a message asked for, taken by the physics thread
        self.door_stationary = self.lift_stationary = True  # the controllers' State, STATIONARY at first
        self.reset()
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        from std_msgs.msg import String
        self.subscriber(name_in(ns, p.string('topic', 'elevator')), String, self.on_elevator)

    def on_elevator(self, msg):
        match = _STOI.match(msg.data)
        if match is None:
            self.ctx.rospy.logerr('%s: Unable to process elevator message[%s]: not a floor number'
                                  % (self.label, msg.data))
            return
        self.requested = int(match.group(1))

    def reset(self):
        self.states = []
        self.lift_prev = self.door_first = None

    def before_physics(self, time):
        floor, self.requested = self.requested, None
        if floor is not None and not self.states:  # MoveToFloor: ignored while busy
            self.states = [['close', None, False], ['move', floor, False], ['open', None, False],
                           ['wait', self.door_wait_time, False], ['close', None, False]]
        (lift, _), (door, _) = [s[:2] for s in self.robot.body.joint_states_raw(
            [self.lift.index, self.door.index])]
        if self.states and self._state_done(self.states[0], time):
            self.states.pop(0)
        self._door(door, time)
        self._lift(lift, time)

    def _state_done(self, state, time):
        kind, argument, started = state
        if not started:  # Start(), and not done this update
            state[2] = True
            if kind in ('open', 'close'):
                self.door_target = OPEN if kind == 'open' else CLOSE
            elif kind == 'move':
                self.floor = argument
            else:
                state[1] = time + argument  # the wait's end
            return False
        if kind in ('open', 'close'):
            return self.door_stationary
        if kind == 'move':
            return self.lift_stationary
        return time >= argument

    def _door(self, position, time):
        if self.door_first is None:  # bootstrap the time
            self.door_first = time
            return
        error = position - self.door_target
        push(self, self.door, self.door_pid.update(error, time - self.door_first))
        self.door_stationary = abs(error) < 0.05

    def _lift(self, position, time):
        if self.lift_prev is None:
            self.lift_prev = time
            return
        error = position - self.floor * self.floor_height
        push(self, self.lift, self.lift_pid.update(error, time - self.lift_prev))
        self.lift_prev = time
        self.lift_stationary = abs(error) < 0.15

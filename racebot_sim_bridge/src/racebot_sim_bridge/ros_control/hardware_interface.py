"""ros_control's RobotHW for a simulated robot, as gazebo_ros_control's DefaultRobotHWSim builds it.

One joint per transmission. Each joint has a state handle (position, velocity, effort) and one
command interface (effort, velocity or position). Positions of revolute and continuous joints are
unwrapped: accumulated by the shortest angular step, never wrapped to ±pi. Before writing,
limits are enforced as joint_limits_interface does for an effort joint without soft limits:
saturate to the URDF effort limit, and allow no effort that pushes further past a position or
velocity limit. No ROS and no PyBullet here: the simulator passes joint states in, efforts out.
"""
import math

EFFORT = 'hardware_interface/EffortJointInterface'
VELOCITY = 'hardware_interface/VelocityJointInterface'
POSITION = 'hardware_interface/PositionJointInterface'
STATE = 'hardware_interface/JointStateInterface'
COMMAND_INTERFACES = (EFFORT, VELOCITY, POSITION)
# JointHandle's interface as a number, compared every update
_EFFORT_MODE, _VELOCITY_MODE, _POSITION_MODE, _OTHER = 0, 1, 2, 3
_MODES = {EFFORT: _EFFORT_MODE, VELOCITY: _VELOCITY_MODE, POSITION: _POSITION_MODE}
_PI = math.pi


def cpp_name(interface):
    """'hardware_interface/EffortJointInterface' -> 'hardware_interface::EffortJointInterface' (as
    list_controllers reports claimed resources)."""
    return interface.replace('/', '::')


def shortest_angular_distance(a, b):
    """Signed smallest angle that takes a to b, in (-pi, pi]."""
    d = math.fmod(b - a, 2.0 * math.pi)
    if d > math.pi:
        d -= 2.0 * math.pi
    elif d <= -math.pi:
        d += 2.0 * math.pi
    return d


def shortest_angular_distance_with_limits(current, target, lower, upper):
    """Error that takes `current` to `target` without leaving [lower, upper] (angles' idea of
    shortest_angular_distance_with_large_limits): the short way round if it stays inside the
    limits, else the long way."""
    delta = shortest_angular_distance(current, target)
    if lower - 1e-12 <= current + delta <= upper + 1e-12:
        return delta
    other = delta - math.copysign(2.0 * _PI, delta) if delta != 0.0 else 0.0
    if lower - 1e-12 <= current + other <= upper + 1e-12:
        return other
    return delta


class HardwareError(ValueError):
    """A controller asked for a joint or an interface this robot does not offer."""


class JointHandle:
    """State of one joint and its command, as the controllers see it.

    When built (CMakeLists.txt), hardware_interface.pxd compiles this class with typed fields: read() and
    limited_command() run every world update for every joint."""

    __slots__ = ('name', 'kind', 'interface', 'lower', 'upper', 'max_effort', 'max_velocity',
                 'position', 'velocity', 'effort', 'command', 'has_position_limits',
                 '_raw_position', '_has_raw', '_wraps', '_angular', '_mode', '_lower', '_upper', '_effort_limit',
                 '_velocity_limit')

    def __init__(self, name, kind, interface, lower=None, upper=None, max_effort=None, max_velocity=None):
        self.name = name
        self.kind = kind  # 'revolute', 'continuous' or 'prismatic'
        self.interface = interface
        self.lower, self.upper = lower, upper
        self.max_effort = max_effort if (max_effort is not None and max_effort > 0) else None
        self.max_velocity = max_velocity if (max_velocity is not None and max_velocity > 0) else None
        self.position = 0.0
        self.velocity = 0.0
        self.effort = 0.0
        self.command = 0.0
        self._raw_position = 0.0
        self._has_raw = False
        # Fixed at construction (the URDF's), read by every update: plain attributes, not properties.
        self.has_position_limits = kind in ('revolute', 'prismatic') and lower is not None and upper is not None \
            and lower < upper
        self._wraps = kind != 'prismatic'  # angles are unwrapped; prismatic positions are taken as they are
        self._angular = kind in ('revolute', 'continuous')
        # The same limits as floats for limited_command (+inf where the URDF sets none).
        self._mode = _MODES.get(interface, _OTHER)
        self._lower = float(lower) if self.has_position_limits else -math.inf
        self._upper = float(upper) if self.has_position_limits else math.inf
        self._effort_limit = float(self.max_effort) if self.max_effort is not None else math.inf
        self._velocity_limit = float(self.max_velocity) if self.max_velocity is not None else math.inf

    def read(self, raw_position, velocity):
        if self._wraps and self._has_raw:
            previous = self._raw_position
            step = raw_position - previous
            if not -_PI < step <= _PI:  # what shortest_angular_distance returns for a step in (-pi, pi]
                step = shortest_angular_distance(previous, raw_position)
            self.position += step
        else:
            self.position = raw_position
        self._raw_position = raw_position
        self._has_raw = True
        self.velocity = velocity

    def reset_position(self, raw_position):
        self._has_raw = False
        self.read(raw_position, 0.0)

    def clamped_position(self, value):
        """`value` within the joint's position limits (as it is without limits)."""
        if self.has_position_limits:
            return min(max(value, self._lower), self._upper)
        return value

    def limited_command(self):
        """The command after joint_limits_interface's saturation (effort) or clamping (others)."""
        cmd = self.command
        if not cmd - cmd == 0.0:  # inf or NaN (x - x is 0 for every finite x)
            return 0.0
        mode = self._mode
        if mode == _EFFORT_MODE:
            lo = -self._effort_limit
            hi = self._effort_limit
            if self.has_position_limits:
                if self.position < self._lower:
                    lo = 0.0
                elif self.position > self._upper:
                    hi = 0.0
            if self.velocity < -self._velocity_limit:
                lo = 0.0
            elif self.velocity > self._velocity_limit:
                hi = 0.0
            return min(max(cmd, lo), hi)
        if mode == _VELOCITY_MODE:
            return min(max(cmd, -self._velocity_limit), self._velocity_limit)
        if mode == _POSITION_MODE:
            return self.clamped_position(cmd)
        return cmd


def position_error(joint, target):
    """effort_controllers/JointPositionController's error: the angle from the joint's position to
    `target` (within its limits, if it has them) or, for a prismatic joint, the difference."""
    if not joint._angular:
        return target - joint.position
    if joint.has_position_limits:
        return shortest_angular_distance_with_limits(joint.position, target, joint._lower, joint._upper)
    return shortest_angular_distance(joint.position, target)


def read_joint_states(handles, states):
    """Each handle reads its joint's state: `states` are PyBullet's getJointStates tuples (position,
    velocity, ...), in the handles' order."""
    for h, s in zip(handles, states):
        h.read(s[0], s[1])


def limited_efforts(handles):
    """The limited command of each (effort) handle, also kept as its effort: what is applied."""
    efforts = []
    for h in handles:
        e = h.limited_command()
        h.effort = e
        efforts.append(e)
    return efforts


class RobotHW:
    """The joints of one robot, from its URDF and transmissions (urdf_model.RobotModel)."""

    def __init__(self, model, hardware_joints):
        """hardware_joints: [(joint_name, interface)] as gazebo_ros_control.robot_hw_sim.hardware_joints gives them."""
        self.model = model  # urdf_model.RobotModel: controllers read geometry from it (diff_drive_controller)
        self.handles = {}
        self.warnings = []
        for joint_name, interface in hardware_joints:
            joint = model.joints[joint_name]
            if interface not in COMMAND_INTERFACES:
                self.warnings.append("joint '%s': hardware interface '%s' is not supported (use one of %s); "
                                     "skipped" % (joint_name, interface, ', '.join(COMMAND_INTERFACES)))
                continue
            if joint.type not in ('revolute', 'continuous', 'prismatic'):
                self.warnings.append("joint '%s' of type '%s' cannot be actuated; transmission skipped"
                                     % (joint_name, joint.type))
                continue
            lim = joint.limit
            self.handles[joint_name] = JointHandle(
                joint_name, joint.type, interface,
                lower=lim.lower if lim else None, upper=lim.upper if lim else None,
                max_effort=lim.effort if lim else None, max_velocity=lim.velocity if lim else None)
        self.names = sorted(self.handles)  # ros_control's resource managers list names in order

    def handle(self, joint_name, interface):
        """The handle a controller claims; errors as ros_control's resource manager words them."""
        h = self.handles.get(joint_name)
        if h is None or (interface != STATE and h.interface != interface):
            known = sorted(n for n, x in self.handles.items() if interface == STATE or x.interface == interface)
            raise HardwareError("Could not find resource '%s' in '%s' (this robot offers: %s)"
                                % (joint_name, cpp_name(interface), ', '.join(known) or 'none'))
        return h

    def interfaces(self):
        return sorted({h.interface for h in self.handles.values()} | {STATE})

    def reset_commands(self):
        for h in self.handles.values():
            h.command = 0.0

"""joint_trajectory_controller's trajectory maths, as ros_controllers noetic-devel does it, without ROS.

A trajectory is one list of segments per joint. A segment joins two states (position and, when both
ends have them, velocity and acceleration) with upstream's QuinticSplineSegment: linear with positions
only, cubic with velocities, quintic with accelerations; sampled before its start it gives the start
position, after its end the end position, both at rest. Times are the controller's clock (here the
simulation time, which is what ros_control's `time` and upstream's controller uptime both count).

Building a trajectory from a trajectory_msgs/JointTrajectory (upstream's initJointTrajectory): the
message starts at header.stamp, or at the next update when the stamp is 0; points already in the past
are dropped; the segments of the running trajectory that are active until the new one starts are
kept, and a bridge segment joins the running trajectory's state at that moment to the first new point
("trajectory replacement"). Continuous joints take the new positions the short way round.

Tolerances (upstream's tolerances.h): per joint a path (state) tolerance and a goal tolerance, each a
position, velocity and acceleration bound where 0 means unchecked; the goal's velocity bound is
`stopped_velocity_tolerance`; and one goal_time tolerance (0: no time limit on reaching the goal).
"""
import bisect
import math
from dataclasses import dataclass, field, replace

from racebot_sim_bridge.kinematics.angles import shortest_angular_distance


class TrajectoryError(ValueError):
    """A trajectory message that cannot be followed; the message is upstream's error string."""


@dataclass(frozen=True)
class StateTolerance:
    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0

    def holds(self, error):
        """error: (position, velocity, acceleration) error; a bound of 0 is not checked."""
        return not ((self.position > 0.0 and abs(error[0]) > self.position)
                    or (self.velocity > 0.0 and abs(error[1]) > self.velocity)
                    or (self.acceleration > 0.0 and abs(error[2]) > self.acceleration))


@dataclass(frozen=True)
class JointTolerances:
    path: StateTolerance = StateTolerance()
    goal: StateTolerance = StateTolerance()
    goal_time: float = 0.0


def _number(value, name):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise TrajectoryError("constraints: '%s' must be a finite number, got %r" % (name, value))
    return float(value)


def tolerances_from_params(constraints, joint_names):
    """The `constraints` parameter dict -> [JointTolerances] in joint order (getSegmentTolerances):
    `<joint>/trajectory` the path position bound, `<joint>/goal` the goal position bound (0 default),
    `stopped_velocity_tolerance` (0.01) the goal velocity bound, `goal_time` (0)."""
    constraints = constraints if isinstance(constraints, dict) else {}
    stopped = _number(constraints.get('stopped_velocity_tolerance', 0.01), 'stopped_velocity_tolerance')
    goal_time = _number(constraints.get('goal_time', 0.0), 'goal_time')
    out = []
    for name in joint_names:
        per = constraints.get(name, {})
        per = per if isinstance(per, dict) else {}
        out.append(JointTolerances(
            path=StateTolerance(position=_number(per.get('trajectory', 0.0), '%s/trajectory' % name)),
            goal=StateTolerance(position=_number(per.get('goal', 0.0), '%s/goal' % name), velocity=stopped),
            goal_time=goal_time))
    return out


def _updated(tol, msg):
    """updateStateTolerances: a positive value replaces the bound, a negative one clears it, 0 keeps it."""
    values = {}
    for key in ('position', 'velocity', 'acceleration'):
        v = getattr(msg, key)
        if v > 0.0:
            values[key] = float(v)
        elif v < 0.0:
            values[key] = 0.0
    return replace(tol, **values)


def tolerances_from_goal(defaults, joint_names, path_tolerance, goal_tolerance, goal_time_tolerance):
    """updateSegmentTolerances: a FollowJointTrajectory goal's JointTolerance lists (by joint name) and
    goal_time_tolerance (s; > 0 replaces, < 0 clears, 0 keeps) over the defaults."""
    out = []
    for name, tol in zip(joint_names, defaults):
        path, goal = tol.path, tol.goal
        for m in path_tolerance:
            if m.name == name:
                path = _updated(path, m)
        for m in goal_tolerance:
            if m.name == name:
                goal = _updated(goal, m)
        goal_time = tol.goal_time
        if goal_time_tolerance < 0.0:
            goal_time = 0.0
        elif goal_time_tolerance > 0.0:
            goal_time = float(goal_time_tolerance)
        out.append(JointTolerances(path, goal, goal_time))
    return out


# -- segments ---------------------------------------------------------------------------------------
def spline_coefficients(start, end, duration):
    """QuinticSplineSegment::computeCoefficients for one joint. start, end: (position, velocity or
    None, acceleration or None); the order used is what both ends have."""
    p0, v0, a0 = start
    p1, v1, a1 = end
    T = duration
    if v0 is None or v1 is None:  # positions only: linear
        return (p0, 0.0 if T == 0.0 else (p1 - p0) / T, 0.0, 0.0, 0.0, 0.0)
    if a0 is None or a1 is None:  # cubic
        if T == 0.0:
            return (p0, v0, 0.0, 0.0, 0.0, 0.0)
        return (p0, v0, (-3.0 * p0 + 3.0 * p1 - 2.0 * v0 * T - v1 * T) / T ** 2,
                (2.0 * p0 - 2.0 * p1 + v0 * T + v1 * T) / T ** 3, 0.0, 0.0)
    if T == 0.0:
        return (p0, v0, 0.5 * a0, 0.0, 0.0, 0.0)
    T2, T3, T4, T5 = T ** 2, T ** 3, T ** 4, T ** 5
    return (p0, v0, 0.5 * a0,
            (-20.0 * p0 + 20.0 * p1 - 3.0 * a0 * T2 + a1 * T2 - 12.0 * v0 * T - 8.0 * v1 * T) / (2.0 * T3),
            (30.0 * p0 - 30.0 * p1 + 3.0 * a0 * T2 - 2.0 * a1 * T2 + 16.0 * v0 * T + 14.0 * v1 * T) / (2.0 * T4),
            (-12.0 * p0 + 12.0 * p1 - a0 * T2 + a1 * T2 - 6.0 * v0 * T - 6.0 * v1 * T) / (2.0 * T5))


def _poly(c, t):
    p = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))))
    v = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])))
    a = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]))
    return p, v, a


@dataclass
class Segment:
    """One joint's segment from start_time to end_time. `goal` is the action goal it serves (None: a
    command from the topic, or holding); `tolerances` apply while it runs (JointTolerances)."""
    start_time: float
    end_time: float
    coefficients: tuple
    time_from_start: float = 0.0
    goal: object = None
    tolerances: JointTolerances = field(default_factory=JointTolerances)

    @classmethod
    def between(cls, start_time, start, end_time, end, time_from_start=0.0):
        if end_time < start_time:
            raise TrajectoryError('Cannot create a segment that ends before it starts (%g < %g)'
                                  % (end_time, start_time))
        return cls(start_time, end_time, spline_coefficients(start, end, end_time - start_time), time_from_start)

    def sample(self, time):
        """(position, velocity, acceleration) at `time` (sampleWithTimeBounds)."""
        t = time - self.start_time
        duration = self.end_time - self.start_time
        if t < 0.0:
            return _poly(self.coefficients, 0.0)[0], 0.0, 0.0
        if t > duration:
            return _poly(self.coefficients, duration)[0], 0.0, 0.0
        return _poly(self.coefficients, t)


def find_segment(segments, time):
    """Index of the segment active at `time` (the last one starting at or before it), None before the first."""
    if not segments or time < segments[0].start_time:
        return None
    return bisect.bisect_right([s.start_time for s in segments], time) - 1


def sample(segments, time):
    """(index or None, state): the active segment's state, or the first segment's when `time` precedes
    the trajectory (upstream's sample())."""
    i = find_segment(segments, time)
    if i is not None:
        return i, segments[i].sample(time)
    return None, segments[0].sample(time)


def hold_trajectory(time, positions):
    """HoldTrajectoryBuilder: each joint held where it is, from `time` on."""
    return [[Segment.between(time, (p, 0.0, 0.0), time, (p, 0.0, 0.0))] for p in positions]


def stop_trajectory(time, positions, velocities, duration):
    """StopTrajectoryBuilder: from the desired state (position, velocity) to rest in `duration`, along the
    first half of the segment that would reverse the velocity in twice that time."""
    out = []
    for p, v in zip(positions, velocities):
        longer = Segment.between(time, (p, v, 0.0), time + 2.0 * duration, (p, -v, 0.0))
        end = longer.sample(time + duration)
        out.append([Segment.between(time, (p, v, 0.0), time + duration, end)])
    return out


def wraparound_offset(previous, following, wraps):
    """wraparoundJointOffset: what to add to a continuous joint's new positions so it does not turn
    whole turns to reach them."""
    if not wraps:
        return 0.0
    return previous + shortest_angular_distance(previous, following) - following


# -- from a message ---------------------------------------------------------------------------------
@dataclass
class Point:
    """A trajectory_msgs/JointTrajectoryPoint, as plain data (time_from_start in seconds)."""
    positions: list
    velocities: list
    accelerations: list
    time_from_start: float


def _check_point(point, n):
    size = len(point.positions)
    if size != n or (point.velocities and len(point.velocities) != size) \
            or (point.accelerations and len(point.accelerations) != size):
        raise TrajectoryError('Size mismatch in trajectory point position, velocity or acceleration data.')
    values = list(point.positions) + list(point.velocities) + list(point.accelerations) + [point.time_from_start]
    if not all(math.isfinite(v) for v in values):
        raise TrajectoryError('Trajectory point at time_from_start %r has a value that is not finite (NaN or '
                              'infinite); send finite positions, velocities, accelerations and times.'
                              % point.time_from_start)


def _joint_state(point, k, offset):
    return (point.positions[k] + offset,
            point.velocities[k] if point.velocities else None,
            point.accelerations[k] if point.accelerations else None)


def build_trajectory(msg_joint_names, points, stamp, time, joint_names, current=None, wraps=None,
                     tolerances=None, goal=None, allow_partial=False):
    """initJointTrajectory. msg_joint_names and points (Point) as the message has them, stamp its
    header time (0: start at `time`); time: the next update's time; joint_names: the controller's;
    current: the running trajectory or None; wraps: per controller joint, True for continuous joints;
    tolerances: [JointTolerances] for the segments (goal-specific ones already applied).
    Returns the new trajectory, or raises TrajectoryError with upstream's message."""
    if not points:
        raise TrajectoryError('Trajectory message contains empty trajectory. Nothing to convert.')
    if any(b.time_from_start <= a.time_from_start for a, b in zip(points, points[1:])):
        raise TrajectoryError('Trajectory message contains waypoints that are not strictly increasing in time.')
    if not allow_partial and len(msg_joint_names) != len(joint_names):
        raise TrajectoryError('Cannot create trajectory from message. It does not contain the expected joints.')
    mapping = joint_mapping(msg_joint_names, joint_names)
    if mapping is None:
        raise TrajectoryError('Cannot create trajectory from message. It does not contain the expected joints.')
    n = len(msg_joint_names)
    for p in points:
        _check_point(p, n)
    start = stamp if stamp else time
    # The first point still ahead: upstream's findPoint (the last point at or before `time`), then one on.
    first = 0
    past = [k for k, p in enumerate(points) if start + p.time_from_start <= time]
    if past:
        first = past[-1] + 1
        if first == len(points):
            raise TrajectoryError('Dropping all %d trajectory point(s), as they occur before the current time.\n'
                                  'Last point is %fs in the past.'
                                  % (len(points), time - (start + points[-1].time_from_start)))
    tolerances = tolerances or [JointTolerances() for _ in joint_names]
    wraps = wraps or [False] * len(joint_names)
    result = [list(segments) for segments in current] if current else [[] for _ in joint_names]
    if current:
        for joint_segments in result:  # what keeps running belongs to the new goal (upstream re-tags it)
            i = find_segment(joint_segments, time)
            for k in range(i if i is not None else 0, len(joint_segments)):
                joint_segments[k] = replace(joint_segments[k], goal=goal)
    for k, joint_id in enumerate(mapping):
        tol = tolerances[joint_id] if goal is not None else JointTolerances()
        new = []
        offset = 0.0
        if current:
            old = current[joint_id]
            last_time = max(start, time)
            _, last_state = sample(old, last_time)
            offset = wraparound_offset(last_state[0], points[first].positions[k], wraps[joint_id])
            i0 = find_segment(old, time)
            i1 = find_segment(old, last_time)
            i0 = 0 if i0 is None else i0
            i1 = 0 if i1 is None else i1
            new.extend(old[i0:i1 + 1])  # still executed, with the goal they had (as upstream)
            bridge = Segment.between(last_time, last_state, start + points[first].time_from_start,
                                     _joint_state(points[first], k, offset))
            bridge.goal, bridge.tolerances = goal, tol
            new.append(bridge)
        for a, b in zip(points[first:], points[first + 1:]):
            seg = Segment.between(start + a.time_from_start, _joint_state(a, k, offset),
                                  start + b.time_from_start, _joint_state(b, k, offset), a.time_from_start)
            seg.goal, seg.tolerances = goal, tol
            new.append(seg)
        if new:
            result[joint_id] = new
    return result


def joint_mapping(msg_joint_names, joint_names):
    """internal::mapping: for each message joint, its index among the controller's joints; None when one
    is not the controller's (or the message names none)."""
    if not msg_joint_names or len(msg_joint_names) > len(joint_names):
        return None
    out = []
    for name in msg_joint_names:
        if name not in joint_names:
            return None
        out.append(joint_names.index(name))
    return out

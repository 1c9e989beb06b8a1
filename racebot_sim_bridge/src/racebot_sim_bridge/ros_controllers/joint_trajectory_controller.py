"""joint_trajectory_controller: {position,velocity,effort}_controllers/JointTrajectoryController, as
ros_controllers noetic-devel (joint_trajectory_controller_impl.h).

A trajectory comes from the `command` topic (trajectory_msgs/JointTrajectory) or the
`follow_joint_trajectory` action (control_msgs/FollowJointTrajectoryAction); each update samples it and
commands the joints: the desired position (PositionJointInterface), or `velocity_ff * desired velocity +
PID(position error, velocity error)` with gains from `gains/<joint>` (Velocity- and EffortJointInterface).
An action goal succeeds when every joint is within its goal tolerance after the last segment; it is
aborted with PATH_TOLERANCE_VIOLATED or GOAL_TOLERANCE_VIOLATED as upstream decides; a new goal or a
command preempts it (canceled); a cancel holds the joints where they are (or brings them to rest in
stop_trajectory_duration). `state` (JointTrajectoryControllerState) at state_publish_rate,
`query_state` (control_msgs/QueryTrajectoryState). The trajectory maths is kinematics/trajectory.py.

Threads: the topic, action and service callbacks run on rospy's threads, the update on the physics
thread. The running trajectory and the active goal change under `_lock`; goal handles are told of an
outcome after the update has let go of it (actionlib takes its own lock, which it holds while calling
our goal callback).
"""
import math
import threading

from control_msgs.msg import (FollowJointTrajectoryAction, FollowJointTrajectoryFeedback,
                              FollowJointTrajectoryResult, JointTrajectoryControllerState)
from control_msgs.srv import QueryTrajectoryState, QueryTrajectoryStateResponse
from trajectory_msgs.msg import JointTrajectory

from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, POSITION, VELOCITY
from racebot_sim_bridge.kinematics import trajectory as jt
from racebot_sim_bridge.kinematics.angles import shortest_angular_distance
from racebot_sim_bridge.ros_control.pid import Pid
from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError, GoalController


def _points(msg):
    return [jt.Point(list(p.positions), list(p.velocities), list(p.accelerations), p.time_from_start.to_sec())
            for p in msg.points]


class JointTrajectoryController(GoalController):
    """The template of the three variants (position, velocity, effort), each subclassed below for its interface."""

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
        names = self.params.get('joints')
        if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
            raise ControllerInitError("Could not find joint name array parameter 'joints' (namespace: %s): set "
                                      "'%s/joints' to a list of the robot's joints (%s)"
                                      % (self.param_ns, self.param_ns, ', '.join(self.hw.names)))
        self.joints = [self._handle(n) for n in names]
        self.joint_names = list(names)
        self.wraps = [j.kind == 'continuous' for j in self.joints]
        rate = self._number('state_publish_rate', 50.0)
        self.state_period = 1.0 / rate if rate > 0 else 0.0
        monitor = self._number('action_monitor_rate', 20.0, positive=True)
        self.monitor_period = 1.0 / monitor
        self.stop_duration = self._number('stop_trajectory_duration', 0.0)
        if self.stop_duration < 0:
            raise ControllerInitError('%s/stop_trajectory_duration must be >= 0 s, got %g'
                                      % (self.param_ns, self.stop_duration))
        self.allow_partial = self._flag('allow_partial_joints_goal', False)
        try:
            self.default_tolerances = jt.tolerances_from_params(self.params.get('constraints'), self.joint_names)
        except jt.TrajectoryError as err:
            raise ControllerInitError('%s/%s' % (self.param_ns, err))
        self.pids, self.velocity_ff = self._closed_loop()
        self._lock = threading.Lock()
        self.running = False
        self.time = 0.0          # the last update's time
        self.period = 0.0        # and its period: the next update comes at time + period
        positions = [j.position for j in self.joints]
        self.trajectory = jt.hold_trajectory(0.0, positions)
        self.desired = [(p, 0.0, 0.0) for p in positions]
        self.active_goal = None  # the accepted goal handle being followed
        self.goal_reached = [False] * len(self.joints)
        self.last_state_publish = 0.0
        self.last_feedback = -math.inf
        self.state_pub = self._pub(self.topic('state'), JointTrajectoryControllerState, 1)
        self.state_msg = JointTrajectoryControllerState(joint_names=list(self.joint_names))
        self._sub(self.topic('command'), JointTrajectory, self._on_command)
        self._topics.append(self.io.service(self.topic('query_state'), QueryTrajectoryState, self._query_state))
        self._topics.append(self.io.action_server(self.topic('follow_joint_trajectory'), FollowJointTrajectoryAction,
                                                  self._on_goal, self._on_cancel))

    def _closed_loop(self):
        """Velocity and effort joints: a PID per joint from gains/<joint> and velocity_ff/<joint> (0)."""
        if self.interface == POSITION:
            return None, None
        pids, ff = [], []
        for name in self.joint_names:
            gains = self._lookup('gains/' + name)
            if not isinstance(gains, dict):
                raise ControllerInitError("Failed to initialize PID gains from ROS parameter server: no gains for "
                                          "joint '%s'; set %s/gains/%s: {p: ..., i: ..., d: ...}"
                                          % (name, self.param_ns, name))
            try:
                pids.append(Pid.from_params(gains, '%s/gains/%s' % (self.param_ns, name)))
            except ValueError as err:
                raise ControllerInitError(str(err))
            ff.append(self._number('velocity_ff/' + name, 0.0))
        return pids, ff

    def claimed_resources(self):
        return [(self.interface, sorted(self.joint_names))]

    # -- life cycle (physics thread) --------------------------------------------------------------
    def starting(self, time):
        with self._lock:
            self.time, self.period = time, 0.0
            self.desired = [(j.position, j.velocity, 0.0) for j in self.joints]
            self.trajectory = self._hold(time)
            self.last_state_publish = time
            self.running = True
        if self.pids is not None:
            for pid, j in zip(self.pids, self.joints):
                pid.reset()
                j.command = 0.0
        else:
            for j in self.joints:
                j.command = j.position

    def _hold(self, time):
        """The hold trajectory: where the joints are, or from the desired state to rest in stop_trajectory_duration."""
        if self.stop_duration == 0.0:
            return jt.hold_trajectory(time, [j.position for j in self.joints])
        return jt.stop_trajectory(time, [d[0] for d in self.desired], [d[1] for d in self.desired], self.stop_duration)

    def update(self, time, period):
        outcome = None
        with self._lock:
            self.time, self.period = time, period
            traj, goal = self.trajectory, self.active_goal
            errors = []
            for i, j in enumerate(self.joints):
                index, d = jt.sample(traj[i], time)
                self.desired[i] = d
                error = (shortest_angular_distance(j.position, d[0]), d[1] - j.velocity, 0.0)
                errors.append(error)
                if goal is None or outcome is not None:
                    continue
                seg = traj[i][index] if index is not None else traj[i][0]
                if seg.goal is not goal:
                    continue
                if time < seg.end_time:
                    if not seg.tolerances.path.holds(error):
                        outcome = ('aborted', FollowJointTrajectoryResult.PATH_TOLERANCE_VIOLATED,
                                   '%s path error %f' % (self.joint_names[i], error[0]))
                elif index == len(traj[i]) - 1:
                    if seg.tolerances.goal.holds(error):
                        self.goal_reached[i] = True
                    elif time >= seg.end_time + seg.tolerances.goal_time:  # goal_time 0: no grace at all
                        outcome = ('aborted', FollowJointTrajectoryResult.GOAL_TOLERANCE_VIOLATED,
                                   '%s goal error %f' % (self.joint_names[i], error[0]))
            if goal is not None and outcome is None and all(self.goal_reached):
                outcome = ('succeeded', FollowJointTrajectoryResult.SUCCESSFUL, '')
            if outcome is not None:
                self.active_goal = None
                self.goal_reached = [False] * len(self.joints)
            desired = list(self.desired)
        self._command(desired, errors, period)
        if outcome is not None:
            self._finish(goal, outcome)
        elif goal is not None and time - self.last_feedback >= self.monitor_period - 1e-9:
            self.last_feedback = time
            goal.publish_feedback(self._feedback(time, desired, errors))
        self._publish_state(time, desired, errors)

    def _command(self, desired, errors, period):
        if self.pids is None:
            for j, d in zip(self.joints, desired):
                j.command = d[0]
            return
        for j, d, e, pid, ff in zip(self.joints, desired, errors, self.pids, self.velocity_ff):
            j.command = d[1] * ff + pid.compute_with_error_dot(e[0], e[1], period)

    @staticmethod
    def _finish(goal, outcome):
        kind, code, text = outcome
        result = FollowJointTrajectoryResult(error_code=code, error_string=text)
        if kind == 'succeeded':
            goal.set_succeeded(result)
        else:
            goal.set_aborted(result, text)

    def _fill(self, msg, time, desired, errors):
        msg.header.stamp = self.io.stamp(time)
        msg.desired.positions = [d[0] for d in desired]
        msg.desired.velocities = [d[1] for d in desired]
        msg.desired.accelerations = [d[2] for d in desired]
        msg.actual.positions = [j.position for j in self.joints]
        msg.actual.velocities = [j.velocity for j in self.joints]
        msg.error.positions = [e[0] for e in errors]
        msg.error.velocities = [e[1] for e in errors]
        return msg

    def _feedback(self, time, desired, errors):
        return self._fill(FollowJointTrajectoryFeedback(joint_names=list(self.joint_names)), time, desired, errors)

    def _publish_state(self, time, desired, errors):
        if self.state_period and self.last_state_publish + self.state_period < time:
            self.last_state_publish += self.state_period
            if self.last_state_publish + self.state_period < time:  # after a pause or a reset: from now on
                self.last_state_publish = time
            self.state_pub.publish(self._fill(self.state_msg, time, desired, errors))

    # -- commands (rospy threads) -----------------------------------------------------------------
    def _replace(self, msg, goal, tolerances):
        """updateTrajectoryCommand under the lock: the new trajectory, or the error string."""
        if not self.running:
            return "Can't accept new commands. Controller is not running."
        next_time = self.time + self.period
        if not msg.points:  # an empty trajectory: stop where the joints are
            self.trajectory = self._hold(self.time)
            for seg in self.trajectory:
                seg[0].goal = goal
            return None
        try:
            self.trajectory = jt.build_trajectory(list(msg.joint_names), _points(msg), msg.header.stamp.to_sec(),
                                                  next_time, self.joint_names, self.trajectory, self.wraps,
                                                  tolerances, goal, self.allow_partial)
        except jt.TrajectoryError as err:
            return str(err)
        return None

    def _on_command(self, msg):
        with self._lock:
            error = self._replace(msg, None, None)
            goal = None
            if error is None:
                goal, self.active_goal = self.active_goal, None
        if error is not None:
            self.io.warn_throttle(self.param_ns, 5.0, '%s: trajectory on %s not followed: %s'
                                  % (self.param_ns, self.topic('command'), error))
        elif goal is not None:
            goal.set_canceled()

    def _on_goal(self, gh):
        request = gh.get_goal()
        names = list(request.trajectory.joint_names)
        with self._lock:
            running = self.running
        if not running:
            gh.set_rejected(FollowJointTrajectoryResult(error_code=FollowJointTrajectoryResult.INVALID_GOAL),
                            "Can't accept new action goals. Controller is not running.")
            return
        if (not self.allow_partial and len(names) != len(self.joint_names)) \
                or jt.joint_mapping(names, self.joint_names) is None:
            text = "Joints on incoming goal don't match the controller joints (%s)." % ', '.join(self.joint_names)
            gh.set_rejected(FollowJointTrajectoryResult(error_code=FollowJointTrajectoryResult.INVALID_JOINTS,
                                                        error_string=text), text)
            return
        tolerances = jt.tolerances_from_goal(self.default_tolerances, self.joint_names, request.path_tolerance,
                                             request.goal_tolerance, request.goal_time_tolerance.to_sec())
        with self._lock:
            error = self._replace(request.trajectory, gh, tolerances)
            previous = None
            if error is None:
                previous, self.active_goal = self.active_goal, None
        if error is not None:
            gh.set_rejected(FollowJointTrajectoryResult(error_code=FollowJointTrajectoryResult.INVALID_GOAL,
                                                        error_string=error), error)
            return
        if previous is not None:
            previous.set_canceled()
        gh.set_accepted()  # before an update can end it: actionlib ends only an active goal
        with self._lock:
            ours = self.running and any(seg.goal is gh for segments in self.trajectory for seg in segments)
            if ours:
                self.active_goal = gh
                self.goal_reached = [False] * len(self.joints)
                self.last_feedback = -math.inf
        if not ours:  # a command or a stop came in between
            gh.set_canceled()

    def _on_cancel(self, gh):
        with self._lock:
            if self.active_goal is None or self.active_goal != gh:
                return
            self.active_goal = None
            self.trajectory = self._hold(self.time)
        gh.set_canceled()

    def _query_state(self, req):
        with self._lock:
            if not self.running:
                raise RuntimeError("Can't sample trajectory. Controller is not running.")
            t = req.time.to_sec()
            res = QueryTrajectoryStateResponse(name=list(self.joint_names))
            for segments in self.trajectory:
                index, (p, v, a) = jt.sample(segments, t)
                if index is None:
                    raise RuntimeError('Requested sample time precedes trajectory start time.')
                res.position.append(p)
                res.velocity.append(v)
                res.acceleration.append(a)
        return res


class PositionJointTrajectoryController(JointTrajectoryController):
    type_name = 'position_controllers/JointTrajectoryController'
    interface = POSITION


class VelocityJointTrajectoryController(JointTrajectoryController):
    type_name = 'velocity_controllers/JointTrajectoryController'
    interface = VELOCITY


class EffortJointTrajectoryController(JointTrajectoryController):
    type_name = 'effort_controllers/JointTrajectoryController'
    interface = EFFORT


TYPES = (PositionJointTrajectoryController, VelocityJointTrajectoryController, EffortJointTrajectoryController)

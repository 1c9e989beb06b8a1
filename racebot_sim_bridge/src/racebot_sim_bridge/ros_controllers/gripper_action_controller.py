"""gripper_action_controller: {position,effort}_controllers/GripperActionController, as ros_controllers
noetic-devel (gripper_action_controller_impl.h).

One joint (`joint`), driven to a control_msgs/GripperCommandAction goal on `gripper_cmd`: the position
variant commands the goal position; the effort variant commands PID(position error, velocity error)
from `gains/<joint>`, clamped to the goal's |max_effort| (0 gives no effort at all, as upstream).
The goal succeeds (reached_goal) once the position is within goal_tolerance; it is aborted (stalled)
when the joint has moved no faster than stall_velocity_threshold for stall_timeout seconds. A new goal
preempts the active one (canceled); a cancel holds the joint where it is.
"""
import threading

from control_msgs.msg import GripperCommandAction, GripperCommandResult

from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, POSITION
from racebot_sim_bridge.ros_control.pid import Pid
from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError, GoalController


def gripper_outcome(error_position, velocity, time, last_movement, goal_tolerance, stall_velocity, stall_timeout):
    """checkForSuccess: ('reached' | 'stalled' | None, the last time the joint moved)."""
    if abs(error_position) < goal_tolerance:
        return 'reached', last_movement
    if abs(velocity) > stall_velocity:
        return None, time
    if time - last_movement > stall_timeout:
        return 'stalled', last_movement
    return None, last_movement


class GripperActionController(GoalController):
    """The template of both variants (position and effort), each subclassed below for its interface."""

    def __init__(self, name, ns, params, hw, io):
        super().__init__(name, ns, params, hw, io)
        joint = self.params.get('joint')
        if not isinstance(joint, str) or not joint:
            raise ControllerInitError("Could not find joint name on param server (namespace: %s): set '%s/joint' to "
                                      "the gripper's joint (%s)" % (self.param_ns, self.param_ns,
                                                                    ', '.join(self.hw.names)))
        self.joint = self._handle(joint)
        self.monitor_period = 1.0 / self._number('action_monitor_rate', 20.0, positive=True)
        self.goal_tolerance = abs(self._number('goal_tolerance', 0.01))
        self.default_max_effort = abs(self._number('max_effort', 0.0))
        self.stall_velocity = self._number('stall_velocity_threshold', 0.001)
        self.stall_timeout = self._number('stall_timeout', 1.0)
        self.pid = None
        if self.interface == EFFORT:
            gains = self._lookup('gains/' + joint)
            if not isinstance(gains, dict):
                raise ControllerInitError("Failed to initialize PID gains from ROS parameter server: set "
                                          "%s/gains/%s: {p: ..., i: ..., d: ...}" % (self.param_ns, joint))
            try:
                self.pid = Pid.from_params(gains, '%s/gains/%s' % (self.param_ns, joint))
            except ValueError as err:
                raise ControllerInitError(str(err))
        self._lock = threading.Lock()
        self.running = False
        self.time = 0.0
        self.target = (self.joint.position, self.default_max_effort)  # (position, max effort), swapped whole
        self.active_goal = None
        self.last_movement = 0.0
        self.computed = 0.0
        self._topics.append(self.io.action_server(self.topic('gripper_cmd'), GripperCommandAction,
                                                  self._on_goal, self._on_cancel))

    def claimed_resources(self):
        return [(self.interface, [self.joint.name])]

    def starting(self, time):
        with self._lock:
            self.target = (self.joint.position, self.default_max_effort)
            self.last_movement = self.time = time
            self.running = True
        if self.pid is not None:
            self.pid.reset()
            self.joint.command = 0.0
        else:
            self.joint.command = self.joint.position

    def update(self, time, period):
        j = self.joint
        outcome = None
        with self._lock:
            self.time = time
            position, max_effort = self.target
            error = position - j.position
            goal = self.active_goal
            if goal is not None:
                outcome, self.last_movement = gripper_outcome(error, j.velocity, time, self.last_movement,
                                                              self.goal_tolerance, self.stall_velocity,
                                                              self.stall_timeout)
                if outcome is not None:
                    self.active_goal = None
        if outcome is not None:
            result = GripperCommandResult(position=j.position, effort=self.computed,
                                          reached_goal=outcome == 'reached', stalled=outcome == 'stalled')
            if outcome == 'reached':
                goal.set_succeeded(result)
            else:
                goal.set_aborted(result)
        if self.pid is None:
            j.command = position
            self.computed = max_effort
        else:
            effort = self.pid.compute_with_error_dot(error, -j.velocity, period)
            self.computed = j.command = min(max_effort, max(-max_effort, effort))

    def _on_goal(self, gh):
        command = gh.get_goal().command
        with self._lock:
            running = self.running
            previous, self.active_goal = (self.active_goal, None) if running else (None, self.active_goal)
        if not running:
            gh.set_rejected(GripperCommandResult(), "Can't accept new action goals. Controller is not running.")
            return
        if previous is not None:
            previous.set_canceled()
        gh.set_accepted()  # before an update can end it: actionlib ends only an active goal
        with self._lock:
            self.active_goal = gh
            self.target = (command.position, abs(command.max_effort))
            self.last_movement = self.time

    def _on_cancel(self, gh):
        with self._lock:
            if self.active_goal is None or self.active_goal != gh:
                return
            self.active_goal = None
            self.target = (self.joint.position, self.default_max_effort)
        gh.set_canceled()


class PositionGripperActionController(GripperActionController):
    type_name = 'position_controllers/GripperActionController'
    interface = POSITION


class EffortGripperActionController(GripperActionController):
    type_name = 'effort_controllers/GripperActionController'
    interface = EFFORT


TYPES = (PositionGripperActionController, EffortGripperActionController)

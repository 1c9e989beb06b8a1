"""The corpus's flight check (checks.py's kind `flight`): a flying robot flown as its users first fly it, judged
from its ground-truth height (the arithmetic is flight.py's)."""
import threading
import time

import rospy

from corpus import flight
from corpus.ros_io import CheckFailed, Commander, service, sim_sleep


class HeightLog:
    """The model's ground-truth height, (sim time, z) from get_model_state, polled at about 50 Hz wall."""

    def __init__(self, getter, model):
        self.getter, self.model, self.samples, self.error = getter, model, [], None
        self.running = True
        self.thread = threading.Thread(target=self._poll, daemon=True)
        self.thread.start()

    def _poll(self):
        while self.running and not rospy.is_shutdown():
            try:
                reply = self.getter(model_name=self.model, relative_entity_name='')
            except rospy.ServiceException as err:
                self.error = str(err)
                return
            if reply.success and (not self.samples or reply.header.stamp.to_sec() > self.samples[-1][0]):
                self.samples.append((reply.header.stamp.to_sec(), reply.pose.position.z))
            time.sleep(0.02)

    def stop(self):
        self.running = False
        self.thread.join()
        if self.error:
            raise CheckFailed('get_model_state(%s) failed while flying: %s' % (self.model, self.error))
        return list(self.samples)


def _call(spec):
    """Calls the service `spec` names ({service, type, request}); CheckFailed when it says it failed."""
    from roslib.message import get_service_class
    cls = get_service_class(spec['type'])
    if cls is None:
        raise CheckFailed('service type %s unknown here (is its package built?)' % spec['type'])
    reply = service(spec['service'], cls)(**spec.get('request', {}))
    if getattr(reply, 'success', True) is False:
        raise CheckFailed('%s answered success=false' % spec['service'])


def check_flight(check, row):
    """A flying robot as its users first fly it (hector_quadrotor's tutorial): its motors enabled through its own
    service, a climb command on cmd_vel, then a zero command (hover), then no command at all. Judged from the
    ground-truth height: the climb rate against the command (over the climb's second half: the first is the
    controllers' rise), the drift while the zero command holds it, and what its own command timeout does: held
    for the timeout, then the estop's descent (flight.estop_drop) `estop_seconds` later."""
    from gazebo_msgs.srv import GetModelState
    getter = service('/gazebo/get_model_state', GetModelState)
    model = check.get('model', row.get('model'))
    if check.get('enable'):
        _call(check['enable'])
    want, tol = float(check['climb']), float(check['tolerance'])
    climb_s, hold_s = float(check['climb_seconds']), float(check['hold_seconds'])
    timeout, estop_s = float(check['command_timeout']), float(check['estop_seconds'])
    drift_max = float(check['hold_drift'])
    log = HeightLog(getter, model)
    cmd = Commander({'cmd_topic': check['cmd_topic'], 'vz': want})
    try:
        t_climb = rospy.get_rostime().to_sec()
        sim_sleep(climb_s)
        t_hold = rospy.get_rostime().to_sec()
        cmd.hold()
        sim_sleep(hold_s)
    finally:
        cmd.stop()  # its last zero commands, then silence
    t_silent = rospy.get_rostime().to_sec()
    try:
        sim_sleep(timeout + estop_s + 0.5)
    finally:
        samples = log.stop()
    climb = flight.rate(samples, t_climb + climb_s / 2, t_hold)
    drift = flight.rate(samples, t_hold + 1.0, t_silent)
    z_silent, z_timeout = flight.height_at(samples, t_silent), flight.height_at(samples, t_silent + timeout * 0.8)
    z_estop = flight.height_at(samples, t_silent + timeout)
    z_end = flight.height_at(samples, t_silent + timeout + estop_s)
    if None in (climb, drift, z_silent, z_timeout, z_estop, z_end):
        raise CheckFailed('too few ground-truth heights (%d samples over %.1f s of sim time)'
                          % (len(samples), samples[-1][0] - samples[0][0] if samples else 0.0))
    drop, expected = z_estop - z_end, flight.estop_drop(float(check['estop_deceleration']), estop_s)
    numbers = ('climb %.3f m/s (commanded %.3f +-%.0f%%) to %.2f m; hold drift %+.3f m/s; after the last command '
               '%.3f m in %.2f s, then %.3f m in the estop\'s %.1f s (expected %.3f +-%.0f%%)'
               % (climb, want, tol * 100, z_silent, drift, z_silent - z_timeout, timeout * 0.8, drop, estop_s,
                  expected, tol * 100 * 3))
    problems = []
    if abs(climb - want) > tol * abs(want):
        problems.append('climb rate %.3f m/s, commanded %.3f' % (climb, want))
    if abs(drift) > drift_max:
        problems.append('drifted %+.3f m/s under a zero command (at most %.3f)' % (drift, drift_max))
    if abs(z_silent - z_timeout) > drift_max * timeout:
        problems.append('moved %.3f m before the command timeout' % (z_silent - z_timeout))
    if abs(drop - expected) > 3 * tol * expected:  # drag and the motors' lag: a looser bound than the climb's
        problems.append('fell %.3f m in the estop, expected %.3f' % (drop, expected))
    if problems:
        raise CheckFailed('; '.join(problems), numbers)
    return numbers

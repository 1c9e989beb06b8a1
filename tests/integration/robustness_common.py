"""Shared helpers of the robustness, faults and soak rostests (not a test node itself).

Waits are bounded in wall time (a shared 2-core machine may be slow); what is judged is in
simulated time or in the text the system wrote (/rosout, service answers, a process's output).
"""
import math
import os
import signal
import subprocess
import threading
import time

import rosgraph
import rospy
from gazebo_msgs.srv import GetModelState, GetWorldProperties
from rosgraph_msgs.msg import Clock, Log

from integration_common import wait_for  # noqa: F401 (re-exported to the robustness tests)

WALL_TIMEOUT = 90.0
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class Rosout:
    """Every /rosout message since start, searchable by level, node and text."""

    def __init__(self, clock=None):
        self.lock = threading.Lock()
        self.messages = []
        self.clock = clock  # a callable giving sim time, or None
        self.last_warning = (0.0, 0.0)  # (wall, sim) when the newest warning or worse arrived here
        self.sub = rospy.Subscriber('/rosout', Log, self._on_log, queue_size=1000)

    def _on_log(self, msg):
        with self.lock:
            self.messages.append(msg)
            if msg.level >= Log.WARN:
                self.last_warning = (time.time(), (self.clock and self.clock()) or 0.0)

    def mark(self):
        """An index: find(..., since=mark) looks only at messages after it."""
        with self.lock:
            return len(self.messages)

    def matching(self, *needles, **kw):
        level, since, node = kw.get('level', Log.DEBUG), kw.get('since', 0), kw.get('node')
        with self.lock:
            found = self.messages[since:]
        return [m for m in found if m.level >= level and (node is None or m.name == node)
                and all(n in m.msg for n in needles)]

    def find(self, *needles, **kw):
        """The first message at least kw['level'] containing every needle (waits kw['timeout'])."""
        timeout = kw.pop('timeout', 30.0)
        level = kw.get('level', Log.DEBUG)
        return wait_for(lambda: (self.matching(*needles, **kw) or [None])[0],
                        'a /rosout message (level >= %d) containing %r' % (level, needles), timeout)


class SimProbe:
    """The simulator seen from outside: /clock and the /gazebo query services."""

    def __init__(self):
        self.clock = None
        self.clock_sub = rospy.Subscriber('/clock', Clock, self._on_clock, queue_size=1)
        self.world_properties = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        self.model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)

    def _on_clock(self, msg):
        self.clock = msg.clock.to_sec()

    def wait_ready(self, timeout=WALL_TIMEOUT):
        # gazebo_ros advertises reset_world last: with it, every gazebo service is there
        rospy.wait_for_service('/gazebo/reset_world', timeout=timeout)
        wait_for(lambda: self.clock is not None, '/clock', timeout)

    def sim_sleep(self, seconds, timeout=WALL_TIMEOUT):
        start = wait_for(lambda: self.clock is not None, '/clock', timeout) and self.clock
        wait_for(lambda: self.clock >= start + seconds, '%g s of sim time' % seconds, timeout)

    def assert_serving(self, test, sim_seconds=0.2):
        """The simulator still answers a query and its clock still advances."""
        res = self.world_properties()
        test.assertTrue(res.success, res.status_message)
        before = wait_for(lambda: self.clock is not None, '/clock') and self.clock
        wait_for(lambda: self.clock >= before + sim_seconds,
                 '/clock to advance %g s of sim time (the simulator must keep running)' % sim_seconds)
        return res

    def state(self, model='racebot'):
        return self.model_state(model, '')

    def assert_state_finite(self, test, model='racebot'):
        res = self.state(model)
        test.assertTrue(res.success, res.status_message)
        p, q, v, w = res.pose.position, res.pose.orientation, res.twist.linear, res.twist.angular
        values = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, w.x, w.y, w.z]
        test.assertTrue(all(math.isfinite(x) for x in values), 'state of %s not finite: %r' % (model, values))
        test.assertLess(abs(p.z), 5.0, '%s left the ground: z = %g' % (model, p.z))
        return res


def yaw_of(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def node_pid(name):
    """The process id of a running ROS node (its XML-RPC getPid), or None."""
    try:
        import xmlrpc.client
        uri = rosgraph.Master('/robustness_test').lookupNode(name)
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid('/robustness_test')
        return pid if code == 1 else None
    except Exception:  # node gone or not yet registered
        return None


def pid_alive(pid):
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    # a zombie (dead, not yet reaped by roslaunch) counts as gone
    try:
        with open('/proc/%d/stat' % pid) as f:
            return f.read().split(')')[-1].split()[0] != 'Z'
    except OSError:
        return False


class Process:
    """A child process (rosrun ...) with its stdout and stderr collected in one text."""

    def __init__(self, args, env=None):
        self.args = args
        self.output = []
        # A Python node's stdout into a pipe is block-buffered: its loginfo lines would reach us only
        # when it exits (a machine whose environment sets PYTHONUNBUFFERED hides this).
        env = dict(os.environ if env is None else env, PYTHONUNBUFFERED='1')
        self.proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     env=env, start_new_session=True)
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in iter(self.proc.stdout.readline, b''):
            self.output.append(line.decode('utf-8', 'replace'))

    @property
    def text(self):
        return ''.join(self.output)

    def wait_output(self, *needles, **kw):
        timeout = kw.get('timeout', WALL_TIMEOUT)
        return wait_for(lambda: all(n in self.text for n in needles),
                        '%r in the output of %s' % (needles, ' '.join(self.args[:3])), timeout)

    def wait_exit(self, timeout=WALL_TIMEOUT):
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            raise AssertionError('%s did not exit within %.0f s; output:\n%s'
                                 % (' '.join(self.args), timeout, self.text[-3000:]))

    def alive(self):
        return self.proc.poll() is None

    def stop(self, sig=signal.SIGINT, timeout=30.0):
        """Signal the process (a ROS node shuts down cleanly on SIGINT); kill it if it lingers."""
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(10)
        self.reader.join(5)
        return self.proc.returncode


def rosrun(package, executable, *args):
    return Process(['rosrun', package, executable] + list(args))

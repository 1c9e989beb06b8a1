#!/usr/bin/env python3
"""Soak: a long drive in the room, as fast as possible, watching memory, logs and the clock.

    make soak                                  30 min of sim time (the full soak)
    python3 tools/soak.py --sim-minutes 0.75   the short form (the test suite runs it)

Starts `roslaunch racebot_gazebo racebot.launch gui:=false teleop:=false` on a master of its own (a
free port) with a copy of the room world whose real_time_update_rate is 0 (as fast as possible),
subscribes to every sensor topic the car offers (laser, IMU, cameras, point clouds), and drives a
scripted route through servo_commands (/ackermann_cmd_mux/output): figure eights, reverse arcs,
speed changes and stops, chosen by sim time. It measures:
  - the resident memory (RSS) of the simulator (the /gazebo node) at rest, after a warm-up and at the end:
    it must grow less than --max-growth percent (5). The warm-up lasts --warmup s of sim time and until
    every sensor topic has delivered WARM_SENSOR_MESSAGES messages. At rest means: physics paused
    (/gazebo/pause_physics), every frame in flight delivered (no sensor message for REST_QUIET s), then
    the median of REST_SAMPLES readings. While the car drives, RSS swings by a quarter of the simulator
    within a second (134 to 178 MB in one 2-minute run: images and point clouds of 2 to 10 MB being
    rendered, queued and sent, their memory given back to the system as each is freed), so any statistic
    of samples taken while driving measures how many frames happen to be in flight, which a machine's
    speed changes: a window-quantile rule read +5.1 % on a slower machine where the 30-minute soak
    read +0.96 %. At rest nothing is in flight and the readings agree to the page; a leak stays. A rest
    is also taken every REST_EVERY s of sim time in between, reported as the curve (warm-up, ..., end).
    The launch runs with glibc's mmap threshold fixed (MEASURED_TUNABLES): by default glibc raises the
    threshold to the largest block freed, so later frames come from the per-thread arenas (each camera
    publishes on a thread of its own) and a freed frame's pages may stay there, resident, until the arena
    trims. Which frames a rest finds held that way is chance: rests stepped up and down by whole frames
    (1875 kB, one 800 x 800 RGB image) from one rest to the next. With the threshold fixed, every frame is
    mapped and unmapped and RSS at rest is the memory in use;
  - every ERROR or FATAL on /rosout_agg, and any node that died (roslaunch's output): none allowed;
  - /clock: it must never go back (the soak does no reset);
  - at the end: the simulator still serves, the seven controllers run, the car's state is finite.
Prints a short report and writes it as JSON under out/soak/ (or --json). Exit status 0 when every
check passed, 1 otherwise. No timed assertion on speed: the real-time factor is only reported.
Run it in a shell where devel/setup.bash is sourced (the Makefile does that).
"""
import argparse
import datetime
import json
import math
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

from bench import stats  # tools/bench, beside this script

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOM_WORLD = os.path.join(ROOT, 'racebot_gazebo', 'worlds', 'room_mini.world')
REST_QUIET = 0.5      # wall s without a sensor message: the frames in flight have been delivered
REST_TIMEOUT = 10.0   # wall s a rest waits for that quiet at most (then it reads anyway, and says so)
REST_SAMPLES = 8      # RSS readings at rest, REST_SAMPLE_PERIOD apart; their median is the rest's RSS
REST_SAMPLE_PERIOD = 0.05
REST_EVERY = 30.0     # sim s between the rests after the warm-up (the memory curve of the report)
# The warm-up also lasts until every sensor topic has delivered this many messages: a pipeline's buffers
# (frames, point clouds) exist only once it has run, and a loaded machine gives the cameras their first
# frames late in sim time (a CI-like run read 175 MB at 20 s, 187.4 MB from 29 s to the end: +7 %).
WARM_SENSOR_MESSAGES = 20
CONTROLLERS = ['left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
               'left_front_wheel_velocity_controller', 'right_front_wheel_velocity_controller',
               'left_steering_hinge_position_controller', 'right_steering_hinge_position_controller',
               'joint_state_controller']
# The route: (speed m/s, steering rad, sim seconds), repeated. Circles of about 0.8 m radius both
# ways (a figure eight around the spawn point), reversing arcs, a straight dash back and forth, stops.
ROUTE = [(0.5, 0.3, 10.0), (0.5, -0.3, 10.0), (0.0, 0.0, 1.0), (-0.3, 0.4, 5.0), (0.0, -0.4, 1.0),
         (0.3, -0.4, 5.0), (0.8, 0.0, 2.0), (0.0, 0.0, 1.0), (-0.8, 0.0, 2.0), (0.2, 0.6, 6.0),
         (0.0, 0.0, 2.0)]
ROUTE_PERIOD = sum(seg[2] for seg in ROUTE)
COMMAND_WALL_PERIOD = 0.1   # s of wall time between two published commands
SAMPLE_WALL_PERIOD = 0.25   # s of wall time between RSS samples while driving (reported, the swing; no verdict)
SENSOR_TYPES = ('sensor_msgs/LaserScan', 'sensor_msgs/Imu', 'sensor_msgs/Image', 'sensor_msgs/PointCloud2')
# glibc.malloc.mmap_threshold fixed at its default 128 KB: also turns off glibc's dynamic threshold (module doc).
MEASURED_TUNABLES = 'glibc.malloc.mmap_threshold=131072'
STARTUP_TIMEOUT = 180.0     # wall s for the launch to bring up the car with its controllers


def route_command(sim_time):
    """(speed, steering) of the route at a sim time."""
    t = sim_time % ROUTE_PERIOD
    for speed, steering, duration in ROUTE:
        if t < duration:
            return speed, steering
        t -= duration
    return 0.0, 0.0


def fast_world(path_out):
    """A copy of the room world, as fast as possible (real_time_update_rate 0)."""
    with open(ROOM_WORLD) as f:
        text = f.read()
    text, n = re.subn(r'<real_time_update_rate>[^<]*</real_time_update_rate>',
                      '<real_time_update_rate>0</real_time_update_rate>', text)
    if n != 1:
        raise SystemExit('soak: %s has no single <real_time_update_rate> to set to 0' % ROOM_WORLD)
    with open(path_out, 'w') as f:
        f.write(text)
    return path_out


def free_port():
    """A TCP port nothing listens on, and no ROS master answers at."""
    for _ in range(20):
        s = socket.socket()
        s.bind(('localhost', 0))
        port = s.getsockname()[1]
        s.close()
        import rosgraph
        if not rosgraph.Master('/soak', master_uri='http://localhost:%d' % port).is_online():
            return port
    raise SystemExit('soak: no free port for a ROS master')


def rss_kb(pid):
    try:
        with open('/proc/%d/status' % pid) as f:
            for line in f:
                if line.startswith('VmRSS:'):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def measured_environ(environ):
    """The launch's environment: `environ` with MEASURED_TUNABLES added to any GLIBC_TUNABLES it sets."""
    env = dict(environ)
    tunables = [t for t in env.get('GLIBC_TUNABLES', '').split(':')
                if t and not t.startswith('glibc.malloc.mmap_threshold=')]
    env['GLIBC_TUNABLES'] = ':'.join(tunables + [MEASURED_TUNABLES])
    return env


def rest_due(driven, warm, rests, every=REST_EVERY):
    """True when the drive, `driven` s of sim time in, should pause for a rest: once warm (`warm`: the sim time
    the warm-up ended, None before), first at once, then every `every` s after the last of `rests`."""
    if warm is None or driven < warm:
        return False
    return not rests or driven >= rests[-1][0] + every


def rest_growth(rests):
    """Growth of the RSS at rest from the first rest (after the warm-up) to the last (the end), in percent;
    None with fewer than two rests."""
    if len(rests) < 2:
        return None
    return 100.0 * (rests[-1][1] - rests[0][1]) / rests[0][1]


class RestMeter:
    """The simulator's RSS at rest (see the module's doc): pause physics, wait until no sensor message came for
    REST_QUIET wall s (or REST_TIMEOUT), read RSS REST_SAMPLES times, resume. `delivered()`: the sensor messages
    received so far; `driven()`: sim s driven."""

    def __init__(self, rospy, pid, delivered, driven):
        from std_srvs.srv import Empty
        self.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        self.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        self.pid, self.delivered, self.driven = pid, delivered, driven

    def __call__(self):
        """(sim time driven, RSS kB) at rest: the median of the readings."""
        self.pause()
        try:
            deadline = time.time() + REST_TIMEOUT
            last, quiet_since = None, time.time()
            while True:
                delivered, now = self.delivered(), time.time()
                if delivered != last:
                    last, quiet_since = delivered, now
                elif now - quiet_since >= REST_QUIET:
                    break
                if now > deadline:
                    print('soak: sensor messages still came %.0f s after the pause' % REST_TIMEOUT, flush=True)
                    break
                time.sleep(REST_SAMPLE_PERIOD)
            readings = []
            for _ in range(REST_SAMPLES):
                readings.append(rss_kb(self.pid) or 0)
                time.sleep(REST_SAMPLE_PERIOD)
            rest = (round(self.driven(), 3), stats.median(readings))
            print('soak: at rest at %.0f s of sim time: RSS %.1f MB (readings %.1f to %.1f MB)'
                  % (rest[0], rest[1] / 1024.0, min(readings) / 1024.0, max(readings) / 1024.0), flush=True)
            return rest
        finally:
            self.unpause()


class Soak:
    def __init__(self, args, run_dir):
        self.args = args
        self.run_dir = run_dir
        self.sim_seconds = args.sim_minutes * 60.0
        self.warmup = args.warmup if args.warmup is not None else max(20.0, 0.1 * self.sim_seconds)
        self.lock = threading.Lock()
        self.clock = None
        self.clock_messages = 0
        self.clock_regressions = []
        self.errors = []
        self.sensor_counts = {}
        self.sensors_warm_at = None  # sim time (driven) when every sensor topic had its warm-up messages
        self.non_finite = {}
        self.launch = None
        self.failures = []

    # -- bring-up ---------------------------------------------------------------------------------
    def start(self):
        port = free_port()
        os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
        os.environ['ROS_LOG_DIR'] = os.path.join(self.run_dir, 'ros_log')
        world = fast_world(os.path.join(self.run_dir, 'room_fast.world'))
        self.launch_log_path = os.path.join(self.run_dir, 'roslaunch.log')
        self.launch_log = open(self.launch_log_path, 'w')
        cmd = ['roslaunch', '-p', str(port), 'racebot_gazebo', 'racebot.launch', 'gui:=false', 'teleop:=false',
               'world_name:=%s' % world]
        print('soak: %s (master on port %d, logs in %s)' % (' '.join(cmd), port, os.path.relpath(self.run_dir, ROOT)),
              flush=True)
        self.launch = subprocess.Popen(cmd, stdout=self.launch_log, stderr=subprocess.STDOUT, start_new_session=True,
                                       env=measured_environ(os.environ))
        import rospy
        self.rospy = rospy
        deadline = time.time() + STARTUP_TIMEOUT
        import rosgraph
        while not rosgraph.Master('/soak').is_online():
            self._check_launch_alive()
            if time.time() > deadline:
                raise SystemExit('soak: the ROS master did not come up')
            time.sleep(0.2)
        rospy.init_node('soak', disable_signals=True)
        from rosgraph_msgs.msg import Clock, Log
        rospy.Subscriber('/clock', Clock, self._on_clock, queue_size=100, tcp_nodelay=True)
        rospy.Subscriber('/rosout_agg', Log, self._on_log, queue_size=1000)
        from controller_manager_msgs.srv import ListControllers
        from gazebo_msgs.srv import GetModelState, GetWorldProperties
        self._wait(lambda: self._service_up('/racebot/controller_manager/list_controllers'),
                   'the car and its controller manager', deadline)
        self.list_controllers = rospy.ServiceProxy('/racebot/controller_manager/list_controllers', ListControllers)
        self.world_properties = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        self.model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        self._wait(lambda: self.running() == set(CONTROLLERS), 'the seven controllers to run', deadline)
        from ackermann_msgs.msg import AckermannDriveStamped
        self.command_msg = AckermannDriveStamped()
        self.command_pub = rospy.Publisher('/ackermann_cmd_mux/output', AckermannDriveStamped, queue_size=10)
        self._wait(lambda: self.command_pub.get_num_connections() > 0, 'servo_commands to subscribe', deadline)
        self.sim_pid = self._node_pid('/gazebo')
        if self.sim_pid is None:
            raise SystemExit('soak: cannot find the process of the simulator (/gazebo)')
        self._subscribe_sensors()
        self.rest = RestMeter(rospy, self.sim_pid, self._delivered, self._driven)

    def _wait(self, condition, what, deadline):
        while not condition():
            self._check_launch_alive()
            if time.time() > deadline:
                raise SystemExit('soak: timed out waiting for %s; see %s' % (what, self.launch_log_path))
            time.sleep(0.2)

    def _check_launch_alive(self):
        if self.launch.poll() is not None:
            raise SystemExit('soak: roslaunch exited (%s); see %s' % (self.launch.returncode, self.launch_log_path))

    def _service_up(self, name):
        try:
            self.rospy.wait_for_service(name, timeout=0.5)
            return True
        except self.rospy.ROSException:
            return False

    def running(self):
        try:
            return {c.name for c in self.list_controllers().controller if c.state == 'running'}
        except self.rospy.ServiceException:
            return set()

    @staticmethod
    def _node_pid(name):
        import rosgraph
        import xmlrpc.client
        try:
            uri = rosgraph.Master('/soak').lookupNode(name)
            code, _, pid = xmlrpc.client.ServerProxy(uri).getPid('/soak')
            return pid if code == 1 else None
        except Exception:  # not registered (yet)
            return None

    def _subscribe_sensors(self):
        rospy = self.rospy
        from sensor_msgs.msg import Imu, LaserScan
        typed = {'sensor_msgs/LaserScan': LaserScan, 'sensor_msgs/Imu': Imu}
        time.sleep(1.0)
        topics = sorted((t, k) for t, k in rospy.get_published_topics() if k in SENSOR_TYPES)
        for topic, kind in topics:
            self.sensor_counts[topic] = 0
            if kind in typed:  # small: read and check the values
                rospy.Subscriber(topic, typed[kind], lambda m, t=topic: self._on_sensor(t, m), queue_size=5)
            else:  # images and clouds: counted, not decoded
                rospy.Subscriber(topic, rospy.AnyMsg, lambda m, t=topic: self._on_sensor(t, None), queue_size=2)
        print('soak: subscribed to %s' % (', '.join(t for t, _ in topics) or 'no sensor topic (none offered)'),
              flush=True)

    # -- callbacks --------------------------------------------------------------------------------
    def _on_clock(self, msg):
        t = msg.clock.to_sec()
        with self.lock:
            if self.clock is not None and t < self.clock:
                self.clock_regressions.append((self.clock, t))
            self.clock = t
            self.clock_messages += 1

    def _on_log(self, msg):
        if msg.level >= msg.ERROR:
            with self.lock:
                self.errors.append('%s: %s' % (msg.name, msg.msg))

    def _on_sensor(self, topic, msg):
        bad = False
        if msg is not None:
            if hasattr(msg, 'ranges'):  # a laser: finite or +-inf (no return), never NaN
                bad = any(r != r for r in msg.ranges)
            else:
                v = msg.linear_acceleration
                bad = not all(math.isfinite(x) for x in (v.x, v.y, v.z))
        with self.lock:
            self.sensor_counts[topic] += 1
            if bad:
                self.non_finite[topic] = self.non_finite.get(topic, 0) + 1

    # -- the drive ----------------------------------------------------------------------------------
    def drive(self):
        """Drive the route for sim_seconds of sim time from now (the start-up has already used some), resting
        once warm, every REST_EVERY s, and at the end."""
        start_wall = time.time()
        with self.lock:
            self.start_sim = self.clock or 0.0
        self.samples, self.rests = [], []
        next_sample = last_report = 0.0
        while True:
            self._check_launch_alive()
            driven = self._driven()
            self._note_warm(driven)
            warm = None if self.sensors_warm_at is None else max(self.warmup, self.sensors_warm_at)
            if driven < self.sim_seconds and rest_due(driven, warm, self.rests):
                self.rests.append(self.rest())
            speed, steering = route_command(driven)
            self.command_msg.drive.speed, self.command_msg.drive.steering_angle = speed, steering
            self.command_pub.publish(self.command_msg)
            now = time.time()
            if now >= next_sample:
                rss = rss_kb(self.sim_pid)
                if rss is None:
                    self.failures.append('the simulator (pid %d) is gone at %.0f s of sim time' % (self.sim_pid,
                                                                                                driven))
                    break
                self.samples.append((round(driven, 3), rss))
                next_sample = now + SAMPLE_WALL_PERIOD
            if now - last_report >= 30.0:
                last_report = now
                print('soak: %6.0f / %.0f s of sim time, RSS %.1f MB' % (driven, self.sim_seconds,
                                                                          self.samples[-1][1] / 1024.0), flush=True)
            if driven >= self.sim_seconds:
                break
            if self.args.wall_timeout and now - start_wall > self.args.wall_timeout:
                self.failures.append('drove only %.0f of %.0f s of sim time in the wall-time limit of %.0f s'
                                     % (driven, self.sim_seconds, self.args.wall_timeout))
                break
            time.sleep(COMMAND_WALL_PERIOD)
        self.wall_seconds = time.time() - start_wall
        self.driven = self._driven()
        if self.sensors_warm_at is None:
            self.failures.append('not every sensor topic delivered %d messages (%s): no steady state to measure '
                                 'memory from' % (WARM_SENSOR_MESSAGES, self.sensor_counts))
        elif self.rests and self.rests[-1][0] < self.driven:
            self.rests.append(self.rest())  # the end
        self.warmup = max(self.warmup, self.sensors_warm_at or 0.0)

    def _driven(self):
        with self.lock:
            return (self.clock or 0.0) - self.start_sim

    def _delivered(self):
        with self.lock:
            return sum(self.sensor_counts.values())

    def _note_warm(self, driven):
        if self.sensors_warm_at is None:
            with self.lock:
                if all(n >= WARM_SENSOR_MESSAGES for n in self.sensor_counts.values()):
                    self.sensors_warm_at = driven

    # -- verdict ----------------------------------------------------------------------------------
    def final_checks(self):
        rospy = self.rospy
        self.command_msg.drive.speed = self.command_msg.drive.steering_angle = 0.0
        self.command_pub.publish(self.command_msg)
        report = {}
        try:
            props = self.world_properties()
            report['models'] = len(props.model_names)
            state = self.model_state('racebot', '')
            p, v = state.pose.position, state.twist.linear
            report['final_position'] = [p.x, p.y, p.z]
            if not (state.success and all(math.isfinite(x) for x in (p.x, p.y, p.z, v.x, v.y, v.z))):
                self.failures.append('the car state is not finite at the end: %r' % report['final_position'])
            running = self.running()
            report['controllers_running'] = len(running)
            if running != set(CONTROLLERS):
                self.failures.append('controllers not running at the end: %s' % sorted(set(CONTROLLERS) - running))
        except (rospy.ServiceException, rospy.ROSException) as err:
            self.failures.append('the simulator does not serve at the end: %s' % err)
        time.sleep(1.0)  # rosout writes what is in flight
        with self.lock:
            live = set(self.errors)
            self.errors += [e for e in self.logged_errors() if not any(m.split(': ', 1)[-1] in e for m in live)]
        return report

    def logged_errors(self):
        """ERROR and FATAL lines of rosout's own log (every node's messages, also those from before this
        script subscribed), read before the shutdown starts."""
        found = []
        for dirpath, _, files in os.walk(os.environ['ROS_LOG_DIR']):
            if 'rosout.log' in files and not os.path.islink(dirpath):
                with open(os.path.join(dirpath, 'rosout.log'), errors='replace') as f:
                    found += [line.strip() for line in f if re.match(r'^\S+ (ERROR|FATAL) ', line)]
        return found

    def stop(self):
        if self.launch is not None and self.launch.poll() is None:
            os.killpg(self.launch.pid, signal.SIGINT)
            try:
                self.launch.wait(60)
            except subprocess.TimeoutExpired:
                os.killpg(self.launch.pid, signal.SIGKILL)
                self.launch.wait(10)
        self.launch_log.close()
        with open(self.launch_log_path, errors='replace') as f:
            text = f.read()
        died = [line.strip() for line in text.splitlines() if 'process has died' in line]
        tracebacks = text.count('Traceback (most recent call last)')
        return died, tracebacks

    def verdict(self, report):
        rests = getattr(self, 'rests', [])
        growth = rest_growth(rests)
        if growth is not None:
            if growth >= self.args.max_growth:
                self.failures.append('simulator RSS at rest grew %.1f %% after warm-up (%.1f -> %.1f MB; limit %g %%)'
                                     % (growth, rests[0][1] / 1024.0, rests[-1][1] / 1024.0, self.args.max_growth))
        elif not self.failures:
            self.failures.append('fewer than two rests after the warm-up of %.0f s of sim time: drive longer '
                                 '(--sim-minutes) or shorten the warm-up (--warmup)' % self.warmup)
        if self.errors:
            self.failures.append('%d ERROR/FATAL log messages, first: %s' % (len(self.errors), self.errors[0]))
        if self.clock_regressions:
            self.failures.append('/clock went back %d times, first %.3f -> %.3f'
                                 % ((len(self.clock_regressions),) + self.clock_regressions[0]))
        for topic, n in self.non_finite.items():
            self.failures.append('%s: %d messages with NaN values' % (topic, n))
        reached = getattr(self, 'driven', 0.0)
        report.update({
            'sim_minutes_target': self.args.sim_minutes,
            'sim_seconds': round(reached, 3),
            'wall_seconds': round(self.wall_seconds, 1),
            'real_time_factor': round(reached / self.wall_seconds, 2) if self.wall_seconds else None,
            'warmup_sim_seconds': self.warmup,
            'rss_warmup_kb': rests[0][1] if rests else None,
            'rss_end_kb': rests[-1][1] if len(rests) > 1 else None,
            'rss_growth_percent': round(growth, 2) if growth is not None else None,
            'rss_rests': rests,
            'allocator': MEASURED_TUNABLES,
            'rss_max_kb': max(r for _, r in self.samples) if self.samples else None,
            'rss_samples': self.samples,
            'clock_messages': self.clock_messages,
            'clock_regressions': len(self.clock_regressions),
            'errors': self.errors[:50],
            'sensor_messages': self.sensor_counts,
            'route_period_sim_seconds': ROUTE_PERIOD,
            'failures': self.failures,
            'passed': not self.failures,
        })
        return report


def stopped(signum, _frame):
    raise KeyboardInterrupt('stopped by signal %d before the end' % signum)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--sim-minutes', type=float, default=30.0, help='sim time to drive (default 30)')
    parser.add_argument('--warmup', type=float, default=None,
                        help='sim seconds of driving (sensors subscribed) before the reference RSS '
                             '(default: 10 %% of the run, at least 20)')
    parser.add_argument('--max-growth', type=float, default=5.0, help='allowed RSS growth after warm-up, %% (5)')
    parser.add_argument('--wall-timeout', type=float, default=0.0, help='give up after this many wall s (0: never)')
    parser.add_argument('--json', help='where to write the report (default out/soak/soak-<time>.json)')
    args = parser.parse_args()
    if args.sim_minutes <= 0:
        parser.error('--sim-minutes must be > 0')
    if ROOT not in os.environ.get('ROS_PACKAGE_PATH', ''):
        sys.exit('soak: source devel/setup.bash first (or use `make soak`)')
    stamp = datetime.datetime.now().strftime('%Y%m%d-%H%M%S')
    run_dir = os.path.join(ROOT, 'out', 'soak', 'run-%s-%gmin' % (stamp, args.sim_minutes))
    os.makedirs(run_dir)
    json_path = args.json or os.path.join(ROOT, 'out', 'soak', 'soak-%s-%gmin.json' % (stamp, args.sim_minutes))
    soak = Soak(args, run_dir)
    report = {}
    # SIGTERM as SIGINT: either ends the soak through the `finally` below, which takes its roslaunch down too
    signal.signal(signal.SIGTERM, stopped)
    try:
        soak.start()
        soak.drive()
        report = soak.final_checks()
    except (SystemExit, KeyboardInterrupt) as err:
        soak.failures.append(str(err) or 'stopped by a signal before the end')
        soak.wall_seconds = getattr(soak, 'wall_seconds', 0.0)
        soak.samples, soak.rests = getattr(soak, 'samples', []), getattr(soak, 'rests', [])
    finally:
        if soak.launch is not None:
            died, tracebacks = soak.stop()
            for line in died:
                soak.failures.append('roslaunch: %s' % line)
            if tracebacks:
                soak.failures.append('%d Python tracebacks in the roslaunch output' % tracebacks)
    report = soak.verdict(report)
    report['run_dir'] = os.path.relpath(run_dir, ROOT)
    os.makedirs(os.path.dirname(os.path.abspath(json_path)), exist_ok=True)
    with open(json_path, 'w') as f:
        json.dump(report, f, indent=1)
    print('\nsoak report (%s)' % os.path.relpath(json_path, ROOT))
    print('  sim time      %.0f s of %.0f s, wall %.0f s, real-time factor %s'
          % (report['sim_seconds'], args.sim_minutes * 60, report['wall_seconds'], report['real_time_factor']))
    if report['rss_warmup_kb']:
        print('  simulator RSS at rest %.1f MB after warm-up (%.0f s), %.1f MB at the end: %+.2f %% (limit %g %%); '
              'while driving up to %.1f MB'
              % (report['rss_warmup_kb'] / 1024.0, report['warmup_sim_seconds'], (report['rss_end_kb'] or 0) / 1024.0,
                 report['rss_growth_percent'] or 0.0, args.max_growth, report['rss_max_kb'] / 1024.0))
        print('  at rest       %s' % ', '.join('%.0f s %.1f MB' % (t, kb / 1024.0) for t, kb in report['rss_rests']))
    print('  /clock        %d messages, %d times backwards' % (report['clock_messages'], report['clock_regressions']))
    print('  errors        %d ERROR/FATAL log messages' % len(soak.errors))
    sensors = ', '.join('%s %d' % kv for kv in sorted(report['sensor_messages'].items()))
    print('  sensors       %s' % (sensors or 'none'))
    failures = '\n    '.join(report['failures'])
    print('  result        %s' % ('PASSED' if report['passed'] else 'FAILED:\n    ' + failures))
    if report['passed'] and not args.json:
        shutil.copyfile(json_path, os.path.join(ROOT, 'out', 'soak', 'latest.json'))
    sys.exit(0 if report['passed'] else 1)


if __name__ == '__main__':
    main()

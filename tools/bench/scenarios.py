"""The measurements that need ROS. Each runs in its own child process (`tools/run_bench.py --scenario
NAME`) with its own master on a free port: rospy binds a process to one master, and other work on
the machine (tests on 11311) stays out of the way.

The bench's node reads the simulator through services and /proc, and (except for fidelity) does
not subscribe to /clock: with /use_sim_time set, rospy would subscribe it, and a /clock subscriber
costs the simulator what we are measuring. So the bench node starts before the launch sets
/use_sim_time (init_node), and sim time comes from /gazebo/get_world_properties.
"""
import contextlib
import json
import math
import os
import random
import struct
import threading
import time

from . import common, profiling, stats
from .common import BenchError
from .ros_node import WORLD_SERVER, GazeboClient, init_node, measure_window, node_pid, wait_controllers

SENSOR_TYPES = ('sensor_msgs/LaserScan', 'sensor_msgs/Image', 'sensor_msgs/CameraInfo',
                'sensor_msgs/PointCloud2', 'sensor_msgs/Imu')
COMMAND_TOPIC = '/ackermann_cmd_mux/output'


# -- speed: ceiling and bridge side by side ---------------------------------------------------------
def speed(p, out):
    from .ceiling import Ceiling
    port = p['port']
    world_file = common.fast_world(common.ROOM_WORLD, os.path.join(out, 'room_fast.world'))
    result = {'world': 'room_mini (real_time_update_rate 0)'}
    with contextlib.ExitStack() as stack:  # stops the launch, then the master, whatever happens
        core = common.roscore(port, os.path.join(out, 'logs', 'speed_roscore.log'))
        stack.callback(core.stop)
        init_node('racebot_bench_speed')  # before the launch sets /use_sim_time
        launch = common.roslaunch([common.write_bridge_launch(out), 'world_name:=' + world_file], port,
                                  os.path.join(out, 'logs', 'speed_roslaunch.log'))
        stack.callback(launch.stop)
        wait_controllers(launch)
        pid = node_pid(WORLD_SERVER, port)
        result['rss_start_bytes'] = common.rss_bytes(pid)
        world = GazeboClient()
        with common.quiet_stdout():
            ceiling = Ceiling(world_file)
        step = ceiling.step_size
        result['step_s'] = step
        time.sleep(p['warmup_s'])
        result['plain'] = _rounds(world, ceiling, pid, p['rounds'], p['window_s'], step)
        if p.get('profile_s'):
            result['profile'] = profiling.profile_world_server(pid, p['profile_s'], out)
        result['sensors'] = _with_sensors(world, ceiling, pid, p, step)
        result['rss_after_sensors_bytes'] = common.rss_bytes(pid)
        result['sim_after_sensors_s'] = world.time()
        ceiling.close()
        # Memory: on to the sim-time mark (sensors unsubscribed again, like at the start).
        target = p['memory_sim_s']
        common.wait_for(lambda: world.time() >= target, p['memory_timeout_s'],
                        'sim time %g s for the memory figure' % target, launch, period=0.5)
        result['memory_sim_s'] = world.time()
        result['rss_end_bytes'] = common.rss_bytes(pid)
    return result


def _rounds(world, ceiling, pid, rounds, window, step):
    """Ceiling and bridge measured in turn (the other paused), `rounds` times: load that comes and
    goes on a shared machine hits both alike. Each figure is the median over the pairs, with its
    spread (min-max) in 'spread'."""
    if rounds < stats.MIN_PAIRS:
        raise BenchError('%d side-by-side rounds asked for; a ratio needs at least %d' % (rounds, stats.MIN_PAIRS))
    out = []
    for k in range(rounds):
        entry = {}
        for part in (('ceiling', 'bridge') if k % 2 == 0 else ('bridge', 'ceiling')):
            if part == 'ceiling':
                world.pause()
                time.sleep(0.1)
                entry['ceiling_steps_per_s'] = ceiling.measure(window)
                world.unpause()
            else:
                time.sleep(0.2)
                entry.update(measure_window(world, pid, window))
        entry['ceiling_rtf'] = entry['ceiling_steps_per_s'] * step
        entry['ratio'] = entry['rtf'] / entry['ceiling_rtf']
        out.append(entry)
    spread = stats.of_pairs(out, ('ceiling_steps_per_s', 'ceiling_rtf', 'rtf', 'cpu', 'ratio'))
    spread['bridge_rtf'], spread['bridge_cpu'] = spread.pop('rtf'), spread.pop('cpu')
    result = {k: v['median'] for k, v in spread.items()}
    result.update(rounds=out, spread=spread)
    return result


def sensor_topics():
    """The world server's sensor topics (name -> type)."""
    import rosgraph
    master = rosgraph.Master('/racebot_bench')
    types = dict(master.getTopicTypes())
    pubs = master.getSystemState()[0]
    return {t: types.get(t) for t, nodes in pubs if WORLD_SERVER in nodes and types.get(t) in SENSOR_TYPES}


# The subscribers the sensors part measures with: the bench's own (any type, a queue of 2) and a plain one, as
# `rostopic hz` subscribes (any type, rospy's default queue, no tcp_nodelay), which is what a user's first look is.
SUBSCRIBERS = {'bench': dict(queue_size=2), 'plain': {}}


def subscribe_counting(topics, subscriber='bench'):
    """Subscribes to every topic (as any type, the SUBSCRIBERS way) and counts its messages -> ({topic: count},
    subscribers), once every subscription is connected."""
    import rospy
    counts = dict.fromkeys(topics, 0)

    def counter(topic):
        def cb(_msg):
            counts[topic] += 1
        return cb
    subs = [rospy.Subscriber(t, rospy.AnyMsg, counter(t), **SUBSCRIBERS[subscriber]) for t in sorted(topics)]
    common.wait_for(lambda: all(s.get_num_connections() > 0 for s in subs), 20, 'sensor subscriptions')
    return counts, subs


# How long every topic gets to deliver its first message. A camera's first frame waits for the render worker
# (a process started with the first frame wanted, its renderer and the scene loaded): seconds on a busy machine.
FIRST_MESSAGE_TIMEOUT_S = 60.0


def wait_first_messages(counts):
    """Waits until every topic in counts has delivered a message -> the wall seconds that took, so that a
    window measures rates, not the start of a sensor. Topics still silent after FIRST_MESSAGE_TIMEOUT_S are
    measured as they are (0 Hz is then a finding, not a slow start)."""
    start = time.perf_counter()
    try:
        common.wait_for(lambda: all(counts.values()), FIRST_MESSAGE_TIMEOUT_S, 'a first message on every sensor topic')
    except common.BenchError:
        pass
    return time.perf_counter() - start


def _with_sensors(world, ceiling, pid, p, step):
    topics = sensor_topics()
    if not topics:
        return {'available': False}
    counts, subs = subscribe_counting(topics)
    try:
        time.sleep(1.0)
        before, w0, s0 = dict(counts), time.perf_counter(), world.time()
        result = _rounds(world, ceiling, pid, p['rounds'], p['window_s'], step)
        wall, sim = time.perf_counter() - w0, world.time() - s0
        result['available'] = True
        result['topics'] = {t: {'type': topics[t], 'wall_hz': (counts[t] - before[t]) / wall,
                                'sim_hz': (counts[t] - before[t]) / sim if sim > 0 else None}
                            for t in sorted(topics)}
        result['note'] = 'sim_hz counts the ceiling phases too, when the simulator is paused; wall_hz likewise'
    finally:
        for s in subs:
            s.unregister()
    return result


# -- real time: the product launch ------------------------------------------------------------------
def realtime(p, out):
    import rosgraph
    port = p['port']
    trace_path = os.path.join(out, 'command_trace.log')
    if os.path.exists(trace_path):
        os.remove(trace_path)
    result = {}
    with contextlib.ExitStack() as stack:  # stops the launch, then the master, whatever happens
        core = common.roscore(port, os.path.join(out, 'logs', 'realtime_roscore.log'))
        stack.callback(core.stop)
        rosgraph.Master('/racebot_bench', master_uri='http://localhost:%d' % port).setParam(
            WORLD_SERVER + '/command_trace', trace_path)
        init_node('racebot_bench_realtime')  # before the launch sets /use_sim_time
        started = time.monotonic()
        launch = common.roslaunch(['racebot_gazebo', 'racebot.launch', 'gui:=false', 'teleop:=false'], port,
                                  os.path.join(out, 'logs', 'realtime_roslaunch.log'))
        stack.callback(launch.stop)
        wait_controllers(launch)
        result['startup_warm_s'] = time.monotonic() - started
        pid = node_pid(WORLD_SERVER, port)
        result['rss_start_bytes'] = common.rss_bytes(pid)
        world = GazeboClient()
        time.sleep(p['settle_s'])
        parts = [measure_window(world, pid, p['part_s']) for _ in range(p['parts'])]
        wall = sum(x['wall_s'] for x in parts)
        result['window'] = {'wall_s': wall, 'rtf': sum(x['sim_s'] for x in parts) / wall,
                            'cpu': sum(x['cpu'] * x['wall_s'] for x in parts) / wall,
                            'parts_rtf': [round(x['rtf'], 4) for x in parts],
                            'parts_cpu': [round(x['cpu'], 4) for x in parts]}
        result['latency'] = command_path(p['commands'], p['command_rate_hz'], trace_path)
        result['rss_end_bytes'] = common.rss_bytes(pid)
    return result


# -- sensors in real time: the old rendering path against the new, one after the other --------------
SENSOR_PATHS = {
    # TinyRenderer in the physics thread, within the default render budget: before the render worker
    'old': {'render_worker': False, 'renderer': 'tiny'},
    # the render worker with EGL when it loads
    'new': {'render_worker': True, 'renderer': 'auto'},
}


def _sensor_report(master):
    """The world server's last sensor report (~sensors/rates), or {} before its first."""
    try:
        return master.getParam(WORLD_SERVER + '/sensors/rates')
    except Exception:  # no report yet
        return {}


def _published(report):
    """{topic: {wall_hz, skipped_per_s}} the world server itself counted over its last report period (5 s): the
    frames it made and handed to its publisher, whoever then received them."""
    return {r['topic']: {'wall_hz': r['wall_hz'], 'skipped_per_s': r['skipped'] / 5.0}
            for r in report.get('topics', [])}


def _plain_subscriber_rates(world, topics, p, master):
    """Every sensor topic subscribed as `rostopic hz` does (SUBSCRIBERS['plain']) for a window: the real-time
    factor, each topic's messages per wall and per sim second, and what the world server published meanwhile."""
    counts, subs = subscribe_counting(topics, 'plain')
    try:
        first_s = wait_first_messages(counts)
        time.sleep(p['settle_s'])
        before, s0, w0 = dict(counts), world.time(), time.perf_counter()
        time.sleep(p['window_s'])
        after, s1, w1 = dict(counts), world.time(), time.perf_counter()
        published = _published(_sensor_report(master))
    finally:
        for s in subs:
            s.unregister()
    wall, sim = w1 - w0, s1 - s0
    return {'rtf': sim / wall, 'first_message_s': first_s, 'published': published,
            'topics': {t: {'wall_hz': (after[t] - before[t]) / wall,
                           'sim_hz': (after[t] - before[t]) / sim if sim > 0 else None} for t in sorted(topics)}}


def sensors_realtime(p, out):
    """racebot.launch in real time with every sensor topic subscribed, rendering the `path` way:
    the real-time factor, each topic's messages per wall second, the CPU of the world server and
    of its render worker, and the load average; before and after those, the same topics through a plain
    subscriber (`plain`, `plain_after`: as `rostopic hz` subscribes), a window of its own each, so that a gap
    between the two subscribers is not the order they were measured in (the render worker's first minute)."""
    import rosgraph
    port, path = p['port'], p['path']
    result = {'path': path}
    with contextlib.ExitStack() as stack:  # stops the launch, then the master, whatever happens
        core = common.roscore(port, os.path.join(out, 'logs', 'sensors_%s_roscore.log' % path))
        stack.callback(core.stop)
        master = rosgraph.Master('/racebot_bench', master_uri='http://localhost:%d' % port)
        for key, value in SENSOR_PATHS[path].items():
            master.setParam(WORLD_SERVER + '/sensors/' + key, value)
        master.setParam(WORLD_SERVER + '/sensors/report_period', 5.0)
        init_node('racebot_bench_sensors_' + path)  # before the launch sets /use_sim_time
        launch = common.roslaunch(['racebot_gazebo', 'racebot.launch', 'gui:=false', 'teleop:=false'], port,
                                  os.path.join(out, 'logs', 'sensors_%s_roslaunch.log' % path))
        stack.callback(launch.stop)
        wait_controllers(launch)
        pid = node_pid(WORLD_SERVER, port)
        world = GazeboClient()
        topics = sensor_topics()
        result['plain'] = _plain_subscriber_rates(world, topics, p, master)
        counts, subs = subscribe_counting(topics)
        result['first_message_s'] = wait_first_messages(counts)
        time.sleep(p['settle_s'])
        before, s0, w0 = dict(counts), world.time(), time.perf_counter()
        c0 = {q: common.cpu_seconds(q) for q in [pid] + common.child_pids(pid)}
        p0, pw0 = time.process_time(), time.perf_counter()  # this process is the subscriber
        time.sleep(p['window_s'])
        after, s1, w1 = dict(counts), world.time(), time.perf_counter()
        c1 = {q: common.cpu_seconds(q) for q in c0 if os.path.exists('/proc/%d' % q)}
        wall = w1 - w0
        result.update(rtf=(s1 - s0) / wall, wall_s=wall, loadavg=common.loadavg(),
                      topics={t: {'type': topics[t], 'wall_hz': (after[t] - before[t]) / wall} for t in sorted(topics)},
                      cpu_world_server=(c1[pid] - c0[pid]) / wall,
                      cpu_children=sum(c1[q] - c0[q] for q in c1 if q != pid) / wall)
        report = _sensor_report(master)
        result['published'] = _published(report)  # frames made, frames skipped
        result['renderer'] = report.get('renderer')
        result['cpu_subscriber'] = (time.process_time() - p0) / (time.perf_counter() - pw0)
        for s in subs:
            s.unregister()
        result['plain_after'] = _plain_subscriber_rates(world, topics, p, master)
    return result


def command_path(n, rate_hz, trace_path):
    """n distinct AckermannDriveStamped at rate_hz through servo_commands; latency from publishing to
    the controllers' callbacks and to the update that applies the new wheel commands, from the world
    server's command trace (~command_trace)."""
    import rospy
    from ackermann_msgs.msg import AckermannDriveStamped
    from racebot_control.wheel_commands import CarGeometry, wheel_commands
    pub = rospy.Publisher(COMMAND_TOPIC, AckermannDriveStamped, queue_size=1000, tcp_nodelay=True)
    common.wait_for(lambda: pub.get_num_connections() > 0, 30, 'servo_commands subscribing to %s' % COMMAND_TOPIC)
    time.sleep(1.0)
    geometry = CarGeometry()
    # distinct, slow (about a metre in all); as float32, what AckermannDrive.speed carries
    speeds = [struct.unpack('f', struct.pack('f', 0.05 + 1e-4 * k))[0] for k in range(n)]
    expected = [wheel_commands(v, 0.0, 'parallel', geometry) for v in speeds]
    sent = []
    msg = AckermannDriveStamped()
    period = 1.0 / rate_hz
    # Each gap is the period +- a quarter of it, at random (seeded): at a strict 10 ms the commands kept one phase
    # to the world server's 2 ms cycle of updates and sleeps (real time), so one run's p50 and p99 were that phase's
    # latency (0.5 / 1.5 ms in one run, 2.0 / 2.1 ms in another), not the spread a command at any time meets.
    jitter = random.Random(20261126)
    next_t = time.monotonic()
    for v in speeds:
        msg.drive.speed = v
        sent.append(time.monotonic())
        pub.publish(msg)
        next_t += period * jitter.uniform(0.75, 1.25)
        delay = next_t - time.monotonic()
        if delay > 0:
            time.sleep(delay)
    # The last command has nothing to overtake it, so an update applies it: waited for, not slept on.
    common.wait_for(lambda: analyse_trace(trace_path, sent, expected)['last_applied'], 30.0,
                    'the last command applied (%s)' % trace_path)
    msg.drive.speed = 0.0
    pub.publish(msg)
    time.sleep(0.3)
    pub.unregister()
    return analyse_trace(trace_path, sent, expected)


def analyse_trace(trace_path, sent, expected):
    wheels = common.CONTROLLERS[:4]
    events = {}  # (event, controller) -> {k: wall time}
    index = {}
    for w_i, name in enumerate(wheels):
        for k, cmds in enumerate(expected):
            index[(name, round(cmds[w_i], 9))] = k
    with open(trace_path) as f:
        for line in f:
            parts = line.split()
            if len(parts) != 4:
                continue
            event, when, controller, value = parts[0], float(parts[1]), parts[2].rsplit('/', 1)[-1], float(parts[3])
            k = index.get((controller, round(value, 9)))
            if k is not None:
                events.setdefault((event, controller), {}).setdefault(k, when)
    arrived = [events.get(('arrived', w), {}) for w in wheels]
    applied = [events.get(('applied', w), {}) for w in wheels]
    delivered = min(len(a) for a in arrived)
    to_callback = [(arrived[0][k] - sent[k]) * 1e3 for k in range(len(sent)) if k in arrived[0]]
    to_applied = [(max(a[k] for a in applied) - sent[k]) * 1e3 for k in range(len(sent))
                  if all(k in a for a in applied)]
    # Where the time goes: to the first controller's callback (bench -> servo_commands -> world
    # server), then until the fourth wheel controller has its command (servo_commands publishes the
    # six one after the other), then until the update that applies it.
    both = [k for k in range(len(sent)) if all(k in a for a in arrived) and all(k in a for a in applied)]
    first = [(min(a[k] for a in arrived) - sent[k]) * 1e3 for k in both]
    spread = [(max(a[k] for a in arrived) - min(a[k] for a in arrived)) * 1e3 for k in both]
    to_update = [(max(a[k] for a in applied) - max(a[k] for a in arrived)) * 1e3 for k in both]
    p50_p99 = lambda xs: {'p50': stats.percentile(xs, 50), 'p99': stats.percentile(xs, 99)}
    return {'sent': len(sent), 'delivered': delivered, 'applied': len(to_applied),
            'last_applied': all(len(sent) - 1 in a for a in applied),
            'callback_ms': dict(p50_p99(to_callback), max=max(to_callback) if to_callback else None),
            'applied_ms': dict(p50_p99(to_applied), max=max(to_applied) if to_applied else None),
            'segments_ms': {'publish_to_first_callback': p50_p99(first),
                            'first_to_fourth_wheel_callback': p50_p99(spread),
                            'last_callback_to_applied': p50_p99(to_update)}}


# -- start-up: cold, roslaunch starts the master ------------------------------------------------------
def startup(p, out):
    port = p['port']
    started = time.monotonic()
    launch = common.roslaunch(['racebot_gazebo', 'racebot.launch', 'gui:=false', 'teleop:=false'], port,
                              os.path.join(out, 'logs', 'startup_%d.log' % p['run']))
    try:
        os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
        common.wait_for(lambda: common.master_online(port), 60, 'the master', launch, period=0.02)
        wait_controllers(launch)
        return {'startup_s': time.monotonic() - started}
    finally:
        launch.stop()


# -- fidelity: through servo_commands, read from /gazebo/model_states ---------------------------------
class Recorder:
    """The racebot's pose and twist from /gazebo/model_states, stamped with sim time on arrival."""

    def __init__(self):
        import rospy
        from gazebo_msgs.msg import ModelStates
        self.lock = threading.Lock()
        self.samples = []
        self.sub = rospy.Subscriber('/gazebo/model_states', ModelStates, self._cb, queue_size=100)

    def _cb(self, msg):
        import rospy
        try:
            i = msg.name.index('racebot')
        except ValueError:
            return
        p, t = msg.pose[i], msg.twist[i]
        s = (rospy.get_time(), p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
             p.orientation.z, p.orientation.w, t.linear.x, t.linear.y, t.linear.z)
        with self.lock:
            self.samples.append(s)

    def take(self):
        with self.lock:
            s, self.samples = self.samples, []
        return s


def fidelity(p, out):
    import rospy
    from ackermann_msgs.msg import AckermannDriveStamped
    port, mode = p['port'], p['mode']
    world_file = common.fast_world(common.EMPTY_WORLD, os.path.join(out, 'empty_fast.world'))
    launch = common.roslaunch([common.write_bridge_launch(out), 'world_name:=' + world_file, 'servo:=true',
                               'steering_mode:=' + mode], port, os.path.join(out, 'logs', 'fidelity_%s.log' % mode))
    result = {'mode': mode, 'world': 'empty (real_time_update_rate 0)'}
    try:
        wait_controllers(launch)  # first: /use_sim_time is set by then
        init_node('racebot_bench_fidelity', sim_time=True)
        world = GazeboClient()
        rec = Recorder()
        pub = rospy.Publisher(COMMAND_TOPIC, AckermannDriveStamped, queue_size=10, tcp_nodelay=True)
        common.wait_for(lambda: pub.get_num_connections() > 0 and rec.sub.get_num_connections() > 0, 30,
                        'servo_commands and model_states connections')

        def drive(speed, angle, settle, duration):
            """From a reset world, the command held for settle + duration s of sim time; the samples
            after settle."""
            world.pause()
            world.reset()
            time.sleep(0.3)  # messages from before the reset arrive and are dropped
            rec.take()
            msg = AckermannDriveStamped()
            msg.drive.speed, msg.drive.steering_angle = speed, angle
            stop = threading.Event()

            def keep_sending():  # a reset restarts the controllers (command 0): keep the command coming
                while not stop.is_set():
                    pub.publish(msg)
                    stop.wait(0.01)
            sender = threading.Thread(target=keep_sending, daemon=True)
            sender.start()
            time.sleep(0.05)
            world.unpause()
            end = settle + duration
            try:
                common.wait_for(lambda: world.time() >= end, p['timeout_s'], 'sim time %g s' % end, launch, 0.02)
            finally:
                stop.set()
                sender.join()
            world.pause()
            time.sleep(0.2)
            samples = [s for s in rec.take() if settle <= s[0] <= end]
            msg.drive.speed = 0.0
            pub.publish(msg)
            if len(samples) < 10:
                raise BenchError('only %d model_states samples for speed %g, steering %g'
                                 % (len(samples), speed, angle))
            return samples

        result['speeds'] = []
        for v in p['speeds']:
            s = drive(v, 0.0, p['speed_settle_s'], p['speed_measure_s'])
            result['speeds'].append(steady_speed(s, v))
        result['circles'] = []
        for angle in p['angles']:
            radius = common.WHEELBASE / math.tan(angle)
            duration = p['circle_turns'] * 2 * math.pi * radius / p['circle_speed']
            if p.get('circle_max_s'):
                duration = min(duration, p['circle_max_s'])
            s = drive(p['circle_speed'], angle, p['circle_settle_s'], duration)
            result['circles'].append(circle(s, angle, radius))
        result['full_lock'] = []
        for angle in p['lock_angles']:
            s = drive(p['lock_speed'], angle, 0.0, p['lock_s'])
            result['full_lock'].append(full_lock(s, angle, p['lock_speed'], p['lock_s']))
        world.unpause()
    finally:
        launch.stop()
    return result


def _yaw(qx, qy, qz, qw):
    return math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))


def rear_axle(s):
    yaw = _yaw(*s[4:8])
    return s[1] + common.REAR_AXLE_X * math.cos(yaw), s[2] + common.REAR_AXLE_X * math.sin(yaw)


def steady_speed(samples, commanded):
    forward = []
    for s in samples:
        yaw = _yaw(*s[4:8])
        forward.append(s[8] * math.cos(yaw) + s[9] * math.sin(yaw))
    mean = sum(forward) / len(forward)
    return {'commanded': commanded, 'measured': mean, 'error_pct': abs(mean - commanded) / abs(commanded) * 100.0,
            'samples': len(forward)}


def fit_circle(points):
    """Least-squares circle (Kasa): centre and radius."""
    import numpy as np
    pts = np.asarray(points, dtype=float)
    x, y = pts[:, 0], pts[:, 1]
    a = np.column_stack([x, y, np.ones_like(x)])
    b = -(x * x + y * y)
    (d, e, f), *_ = np.linalg.lstsq(a, b, rcond=None)
    cx, cy = -d / 2.0, -e / 2.0
    return (float(cx), float(cy)), float(math.sqrt(max(cx * cx + cy * cy - f, 0.0)))


def circle(samples, angle, reference):
    points = [rear_axle(s) for s in samples]
    centre, radius = fit_circle(points)
    step = max(1, len(points) // 600)
    return {'steering_rad': angle, 'reference_m': reference, 'measured_m': radius,
            'error_pct': abs(radius - reference) / reference * 100.0, 'centre': centre,
            'arc_rad': _arc(points, centre), 'trajectory': [[round(x, 4), round(y, 4)] for x, y in points[::step]]}


def _arc(points, centre):
    total, prev = 0.0, None
    for x, y in points:
        a = math.atan2(y - centre[1], x - centre[0])
        if prev is not None:
            d = math.remainder(a - prev, 2 * math.pi)
            total += d
        prev = a
    return abs(total)


def full_lock(samples, angle, speed, duration):
    finite = all(math.isfinite(v) for s in samples for v in s)
    tilt = [math.degrees(math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (s[4] ** 2 + s[5] ** 2))))) for s in samples]
    max_tilt = max(tilt) if finite else None
    max_z = max(s[3] for s in samples) if finite else None
    return {'steering_rad': angle, 'speed': speed, 'sim_s': duration, 'finite': finite,
            'max_tilt_deg': max_tilt, 'max_z_m': max_z, 'samples': len(samples),
            'ok': bool(finite and max_tilt < 45.0 and max_z < 0.5)}


# -- determinism: the in-process simulator, one run per process ----------------------------------------
def determinism(p, out):
    from . import inprocess
    with common.quiet_stdout():
        trajectory = inprocess.scripted_run(common.ROOM_WORLD, p['sim_s'])
    with open(p['trajectory_file'], 'w') as f:
        json.dump(trajectory, f)
    return {'samples': len(trajectory)}


def fleet(p, out):
    from .fleet import fleet as run
    return run(p, out)


def big_world(p, out):
    from .big_world import scenario
    return scenario(p, out)


def controllers(p, out):
    from .controller_cost import measure
    return measure(p, out)


SCENARIOS = {'speed': speed, 'realtime': realtime, 'sensors': sensors_realtime, 'startup': startup,
             'fidelity': fidelity,
             'determinism': determinism, 'fleet': fleet, 'big_world': big_world, 'controllers': controllers}

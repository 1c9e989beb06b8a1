#!/usr/bin/env python3
"""How long the physics stands still while controllers load (issue 18): the racebot stepping as fast
as possible in a thread, the tutorial's seven controllers loaded and unloaded ROUNDS times through
the controller manager against a real master (parameter reads, publishers, subscribers). Prints,
during the loads and for 2 s without them: how long the stepping thread waited for the controller
manager's lock (the stall itself), steps per second, and the wall gaps between consecutive
Simulator.step calls (on a shared machine the longest gap is mostly the scheduler's).

    source devel/setup.bash; ROS_MASTER_URI=http://localhost:PORT tools/measure_load_stall.py [ROUNDS]
(a master must run at ROS_MASTER_URI: roscore -p PORT).
"""
import os
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import rospy  # noqa: E402

from bench import common  # noqa: E402
from racebot_sim_bridge.description import sdf_reader  # noqa: E402
from racebot_sim_bridge.ros_control.controller_io import RosIO  # noqa: E402
from racebot_sim_bridge.engine.simulator import Simulator  # noqa: E402
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin  # noqa: E402


class _Log:
    error = warn = info = staticmethod(lambda msg: None)


class WaitTimedLock:
    """The controller manager's lock, recording how long the stepping thread waits for it."""

    def __init__(self, lock):
        self.lock, self.waits, self.stepper = lock, [], None

    def __enter__(self):
        begin = time.perf_counter()
        self.lock.acquire()
        if threading.current_thread() is self.stepper:
            self.waits.append(time.perf_counter() - begin)
        return self

    def __exit__(self, *exc):
        self.lock.release()


def _get_param(path):
    try:
        return rospy.get_param(path)
    except KeyError:
        return None


def step_gaps(sim, action, lock):
    """Runs action() while a thread steps sim; (wall gaps between consecutive steps in s, wall time)."""
    stamps, done = [], threading.Event()

    def stepping():
        while not done.is_set():
            sim.step()
            stamps.append(time.perf_counter())
    thread = threading.Thread(target=stepping)
    lock.stepper, lock.waits = thread, []
    thread.start()
    begin = time.perf_counter()
    try:
        action()
    finally:
        wall = time.perf_counter() - begin
        done.set()
        thread.join()
    return [b - a for a, b in zip(stamps, stamps[1:])], wall


def describe(gaps, wall, lock):
    gaps = sorted(gaps)
    return ('physics waited for the controller manager %6.1f ms in all, at most %5.1f ms at once; '
            % (sum(lock.waits) * 1e3, max(lock.waits) * 1e3)
            + '%5.0f steps/s, longest gap %5.1f ms, 99.9th percentile %5.2f ms, gaps > 5 ms: %d'
            % (len(gaps) / wall, gaps[-1] * 1e3, gaps[int(len(gaps) * 0.999)] * 1e3, sum(g > 0.005 for g in gaps)))


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    rospy.init_node('load_stall_probe', disable_rostime=True, disable_signals=True)
    params = common.controller_params()
    for name, value in params.items():
        rospy.set_param('%s/%s' % (common.NAMESPACE, name), value)
    world = os.path.join(HERE, '..', 'racebot_sim_bridge', 'worlds', 'empty.world')
    sim = Simulator(sdf_reader.load_world(world), RosIO(rospy), _Log, _get_param)
    GazeboRosControlPlugin.attach(sim)
    cm = sim.spawn_urdf('racebot', common.render_racebot(), '').control.cm
    cm.lock = lock = WaitTimedLock(cm.lock)

    def loads():
        for _ in range(rounds):
            for name in common.CONTROLLERS:
                assert cm.load(name), name
            for name in common.CONTROLLERS:
                assert cm.unload(name), name

    print('idle (2 s):           ' + describe(*step_gaps(sim, lambda: time.sleep(2.0), lock), lock))
    gaps, wall = step_gaps(sim, loads, lock)
    print('%3d loads + unloads:  ' % (rounds * len(common.CONTROLLERS)) + describe(gaps, wall, lock)
          + ' (%.2f s)' % wall)
    sim.close()


if __name__ == '__main__':
    main()

#!/usr/bin/env python3
"""The first thing a newcomer types: README.md's first `rostopic pub -r 10 /ackermann_cmd_mux/output ...` command,
read from the README and run as it is written (a real `rostopic pub` process) once the seven controllers run.
For 30 s of sim time (it drives a circle: more time repeats it) the car must drive (more than 10 m), stay upright
(roll and pitch under 0.3 rad) and keep its centre at least CLEARANCE from every wall and object of the room (their
footprints from the world file, as `make demo` draws them). The command the README had before (speed 0.5, steering
0.3) met the wall at y 2.2 after about 4 s and fails this test."""
import importlib.util
import math
import os
import re
import signal
import subprocess
import sys
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.msg import ModelStates

from integration_common import wait_for

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
README = os.path.join(REPO, 'README.md')
DRIVE_SECONDS = 30.0  # 60 s until 2026-12-03: the same circle twice as often, 72 CPU s of make test
CLEARANCE = 0.35  # m from the car's centre: half its length (0.26 m wheelbase + wheels) and a margin
MIN_DISTANCE = 10.0  # of the 15 m that 0.5 m/s covers
CONTROLLERS = 7


def readme_drive_command(text):
    """The README's first `rostopic pub -r ... /ackermann_cmd_mux/output` command, continuation lines joined."""
    joined = re.sub(r'\\\n\s*', ' ', text)
    for line in joined.splitlines():
        if line.strip().startswith('rostopic pub -r') and '/ackermann_cmd_mux/output' in line:
            return line.strip()
    raise AssertionError('README.md has no `rostopic pub -r ... /ackermann_cmd_mux/output` command')


def footprints():
    spec = importlib.util.spec_from_file_location('racebot_demo', os.path.join(REPO, 'tools', 'demo.py'))
    demo = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(demo)
    shapes = demo.wall_footprints(demo.WORLD)
    return [s for s in shapes if all(abs(x) < 50 and abs(y) < 50 for x, y in s)]  # not the ground plane


def distance_to_segment(p, a, b):
    ax, ay = b[0] - a[0], b[1] - a[1]
    length2 = ax * ax + ay * ay
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * ax + (p[1] - a[1]) * ay) / length2))
    return math.hypot(p[0] - a[0] - t * ax, p[1] - a[1] - t * ay)


def clearance(point, shapes):
    """(distance, shape index) of the nearest outline edge to `point`."""
    return min((distance_to_segment(point, a, b), i) for i, s in enumerate(shapes) for a, b in zip(s, s[1:]))


class ReadmeDriveTest(unittest.TestCase):
    def test_the_readme_command_circles_clear_of_the_walls_for_a_minute(self):
        rospy.init_node('readme_drive_test')
        with open(README) as f:
            command = readme_drive_command(f.read())
        poses = []

        def on_states(msg):
            if 'racebot' in msg.name:
                p = msg.pose[msg.name.index('racebot')]
                q = p.orientation
                roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y))
                pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
                poses.append((rospy.get_time(), p.position.x, p.position.y, roll, pitch))

        rospy.Subscriber('/gazebo/model_states', ModelStates, on_states, queue_size=10)
        srv = '/racebot/controller_manager/list_controllers'
        rospy.wait_for_service(srv, timeout=120)
        list_controllers = rospy.ServiceProxy(srv, ListControllers)
        wait_for(lambda: sum(c.state == 'running' for c in list_controllers().controller) == CONTROLLERS,
                 'the seven controllers', timeout=120)
        wait_for(lambda: poses, '/gazebo/model_states')
        start = rospy.get_time()
        pub = subprocess.Popen(['bash', '-c', 'exec ' + command], start_new_session=True,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        try:
            wait_for(lambda: rospy.get_time() >= start + DRIVE_SECONDS or pub.poll() is not None,
                     '%.0f s of sim time' % DRIVE_SECONDS, timeout=DRIVE_SECONDS * 5)
            if pub.poll() is not None:
                self.fail('the README command ended early: %r\n%s'
                          % (command, pub.stderr.read().decode(errors='replace')))
        finally:
            if pub.poll() is None:
                os.killpg(pub.pid, signal.SIGINT)
                pub.wait(timeout=10)
        drive = [p for p in poses if p[0] >= start]
        self.assertGreater(len(drive), 100, 'too few poses from /gazebo/model_states')
        distance = sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(drive, drive[1:]))
        self.assertGreater(distance, MIN_DISTANCE, 'the README command (%s) drove only %.1f m in %.0f s'
                           % (command, distance, DRIVE_SECONDS))
        shapes = footprints()
        nearest, t, x, y = min((clearance((x, y), shapes)[0], t, x, y) for t, x, y, _, _ in drive)
        self.assertGreaterEqual(nearest, CLEARANCE, 'the README command (%s) took the car within %.2f m of a wall '
                                'or object at (%.2f, %.2f), %.1f s into the drive'
                                % (command, nearest, x, y, t - start))
        worst = max(max(abs(r), abs(p)) for _, _, _, r, p in drive)
        self.assertLess(worst, 0.3, 'the car tipped: roll or pitch %.2f rad' % worst)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'readme_drive', ReadmeDriveTest, sys.argv)

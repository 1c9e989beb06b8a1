#!/usr/bin/env python3
"""Shutdown is always clean: `roslaunch racebot_gazebo racebot.launch gui:=false teleop:=false` started ITERATIONS
times, each on a master of its own, and stopped with SIGINT (Ctrl-C) at a random moment (seeded: the same moments
every run) from EARLIEST to LATEST wall seconds after the world server's first /clock: mid-spawn, mid-publish,
while the camera renders. Subscribers of /clock, /scan and the camera (rostopic, as a user would) get SIGINT at the
same moment, so connections drop exactly while the world server writes to them, as when roslaunch stops every node
at once. Every process the launch started (the world server, its render worker, the other nodes) must be gone within
EXIT_LIMIT seconds of the SIGINT. Before the fix a SIGINT that came inside a publish left the world server waiting for
a lock its own interrupted publish held: roslaunch killed it only 15-17 s later (SIGTERM, then SIGKILL), one Ctrl-C
in ten."""
import os
import random
import signal
import socket
import subprocess
import sys
import time
import unittest

import rostest

ITERATIONS = 6  # 8 until 2026-12-03: 144 s of make test; each start costs a launch (12 CPU s)
EARLIEST, LATEST = 0.3, 4.0
EXIT_LIMIT = 8.0
START_LIMIT = 120.0
SUBSCRIBED = ('/clock', '/scan', '/rrbot/camera1/image_raw')


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def descendants(pid):
    """Every process below `pid` (children first found through /proc's children lists)."""
    found, todo = [], [pid]
    while todo:
        parent = todo.pop()
        try:
            tasks = os.listdir('/proc/%d/task' % parent)
        except OSError:
            continue
        for task in tasks:
            try:
                with open('/proc/%d/task/%s/children' % (parent, task)) as f:
                    kids = [int(k) for k in f.read().split()]
            except OSError:
                kids = []
            found += kids
            todo += kids
    return found


def alive(pid):
    try:
        with open('/proc/%d/stat' % pid) as f:
            return f.read().split(')')[-1].split()[0] != 'Z'
    except OSError:
        return False


def command_line(pid):
    try:
        with open('/proc/%d/cmdline' % pid, 'rb') as f:
            return f.read().replace(b'\0', b' ').decode(errors='replace')[:160]
    except OSError:
        return '?'


def first_clock(env, deadline):
    """True once a /clock message came (rostopic fails at once while roslaunch's master is not up yet)."""
    while time.time() < deadline:
        try:
            echo = subprocess.run(['rostopic', 'echo', '-n', '1', '/clock'], env=env, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL, timeout=max(1.0, deadline - time.time()))
            if echo.returncode == 0:
                return True
        except subprocess.TimeoutExpired:
            return False
        time.sleep(0.2)
    return False


class ShutdownStressTest(unittest.TestCase):
    def run_once(self, rng, index):
        port = free_port()
        env = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port, ROS_HOSTNAME='localhost')
        launch = subprocess.Popen(['roslaunch', '-p', str(port), 'racebot_gazebo', 'racebot.launch', 'gui:=false',
                                   'teleop:=false'], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                  start_new_session=True)
        subscribers, processes = [], []
        try:
            self.assertTrue(first_clock(env, time.time() + START_LIMIT),
                            'iteration %d: no /clock from racebot.launch in %.0f s' % (index, START_LIMIT))
            subscribers = [subprocess.Popen(['rostopic', 'hz', topic], env=env, stdout=subprocess.DEVNULL,
                                            stderr=subprocess.DEVNULL, start_new_session=True)
                           for topic in SUBSCRIBED]
            time.sleep(rng.uniform(EARLIEST, LATEST))
            processes = descendants(launch.pid)
            for proc in [launch] + subscribers:
                proc.send_signal(signal.SIGINT)
            deadline = time.time() + EXIT_LIMIT
            while time.time() < deadline and any(alive(p) for p in processes):
                time.sleep(0.05)
            left = [p for p in processes if alive(p)]
            self.assertFalse(left, 'iteration %d: %.0f s after SIGINT these processes of racebot.launch still ran:\n%s'
                             % (index, EXIT_LIMIT, '\n'.join(command_line(p) for p in left)))
        finally:  # nothing outlives the test: roslaunch's nodes each have a session of their own
            for proc in [launch] + subscribers:
                if proc.poll() is None:
                    os.killpg(proc.pid, signal.SIGKILL)
                proc.wait(10)
            for pid in processes:
                if alive(pid):
                    os.kill(pid, signal.SIGKILL)

    def test_every_process_ends_within_seconds_of_a_sigint_at_any_moment(self):
        rng = random.Random(37)
        for index in range(ITERATIONS):
            self.run_once(rng, index)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'shutdown_stress', ShutdownStressTest, sys.argv)

#!/usr/bin/env python3
"""The PyBullet window (our gzclient) of `racebot.launch gui:=true`, in a private Xvfb.

The test starts Xvfb (its screen kept in a file: -fbdir) and then the real racebot.launch with
gui:=true on rostest's master, and checks what a user of `make run` relies on:
- the window opens in a process of its own, a child of the simulator, niced below it, and
  /gazebo/get_world_properties says rendering is enabled;
- it shows the simulation: the screen stays still while the car stands, and changes when the car
  is moved (the camera follows it);
- closing the window leaves the simulation running: /clock goes on, the services answer,
  rendering_enabled turns false, and the simulator says on /rosout that the window closed and the
  simulation goes on without it. PyBullet's window does not take part in WM_DELETE_WINDOW (it sets
  no WM_PROTOCOLS), so a window manager's close button kills its X connection (XKillClient), which
  is what `xdotool windowkill` does here; Xlib then ends the window's process.
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from rosgraph_msgs.msg import Log

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from keyboard_teleop_xvfb import screen_pixels, start_xvfb, stop_xvfb  # noqa: E402
from robustness_common import ROOT, Rosout, SimProbe, node_pid, pid_alive, wait_for  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, 'tools'))
from bench.common import child_pids  # noqa: E402

VIEWER_MODULE = 'racebot_sim_bridge.viewer_process'
START_TIMEOUT = 120.0
# Where the car is put (x, y, quaternion z, w): with the camera 1.5 m behind it, nothing in between.
SPAWN_SPOT = (0.0, 0.0, 0.0, 1.0)              # where racebot.launch spawns it
TURNED_SPOT = (0.3, 0.0, 0.2588190, 0.9659258)  # a little ahead, turned 30 degrees left
SCREENS = os.path.join(ROOT, 'out', 'test-results', 'viewer-screens')  # what the window showed, for a reader


def command_line(pid):
    try:
        with open('/proc/%d/cmdline' % pid, 'rb') as f:
            return f.read().replace(b'\0', b' ').decode('utf-8', 'replace')
    except OSError:
        return ''


def niceness(pid):
    with open('/proc/%d/stat' % pid) as f:
        return int(f.read().rsplit(')', 1)[1].split()[16])


class ViewerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.fbdir = tempfile.mkdtemp(prefix='racebot_viewer_fb_')
        cls.xvfb, cls.display = start_xvfb(fbdir=cls.fbdir, screen='1280x1024x24')  # PyBullet's window: 1024 x 768
        env = dict(os.environ, DISPLAY=cls.display)
        cls.launch_log = open(os.path.join(cls.fbdir, 'roslaunch.log'), 'w')
        cls.launch = subprocess.Popen(['roslaunch', 'racebot_gazebo', 'racebot.launch', 'gui:=true', 'teleop:=false'],
                                      env=env, stdout=cls.launch_log, stderr=subprocess.STDOUT)
        rospy.init_node('viewer_test', anonymous=True)
        cls.rosout = Rosout()
        cls.sim = SimProbe()
        cls.sim.wait_ready(START_TIMEOUT)
        rospy.wait_for_service('/gazebo/set_model_state', START_TIMEOUT)
        cls.set_model_state = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)
        wait_for(lambda: 'racebot' in cls.sim.world_properties().model_names, 'the car spawned', START_TIMEOUT)
        cls.sim_pid = wait_for(lambda: node_pid('/gazebo'), "the simulator's process id", START_TIMEOUT)
        cls.viewer_pid = wait_for(lambda: next((p for p in child_pids(cls.sim_pid) if VIEWER_MODULE in command_line(p)),
                                               None), 'the window process, a child of the simulator', START_TIMEOUT)

    @classmethod
    def tearDownClass(cls):
        if cls.launch.poll() is None:
            cls.launch.send_signal(signal.SIGINT)
            try:
                cls.launch.wait(60)
            except subprocess.TimeoutExpired:
                cls.launch.kill()
                cls.launch.wait()
        cls.launch_log.close()
        stop_xvfb(cls.xvfb)
        shutil.rmtree(cls.fbdir, ignore_errors=True)

    def xdotool(self, *args):
        return subprocess.run(['xdotool'] + list(args), env=dict(os.environ, DISPLAY=self.display),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=20)

    def window_ids(self):
        return self.xdotool('search', '--name', 'Bullet Physics').stdout.split()

    @staticmethod
    def screen(name):
        """The Xvfb screen now, also saved as SCREENS/<name>.png."""
        import matplotlib
        matplotlib.use('Agg')
        from matplotlib import pyplot
        pixels = screen_pixels(ViewerTest.fbdir)
        os.makedirs(SCREENS, exist_ok=True)
        pyplot.imsave(os.path.join(SCREENS, name + '.png'), pixels)
        return pixels

    def window_centre(self):
        """(x, y) on the screen of the window's centre; looked up once (nothing moves the window)."""
        if getattr(ViewerTest, 'centre', None) is None:
            out = self.xdotool('getwindowgeometry', '--shell', self.window_ids()[0]).stdout
            geometry = dict(line.split('=', 1) for line in out.split())
            ViewerTest.centre = (int(geometry['X']) + int(geometry['WIDTH']) // 2,
                                 int(geometry['Y']) + int(geometry['HEIGHT']) // 2)
        return ViewerTest.centre

    def car_at_centre(self, screen):
        """Share of car-blue pixels in the window's central box, where the following camera keeps the car."""
        cx, cy = self.window_centre()
        box = screen[cy - 20:cy + 30, cx - 25:cx + 25].astype(np.int16)
        blue = (box[:, :, 2] > box[:, :, 0] + 60) & (box[:, :, 2] > box[:, :, 1] + 60)
        return float(blue.mean())

    def still_screen(self):
        """(screen,) if it did not change in a second (less than 2 %), else None."""
        first = self.screen('1-car-standing')
        time.sleep(1.0)
        return (first,) if self.changed_share(first, self.screen('2-a-second-later')) < 0.02 else None

    def changed_share(self, a, b):
        return float((np.abs(a.astype(np.int16) - b) > 8).any(axis=2).mean())

    def test_1_the_window_is_a_niced_process_of_its_own(self):
        self.assertNotEqual(self.viewer_pid, self.sim_pid)
        wait_for(self.window_ids, 'a "Bullet Physics" window on %s' % self.display, START_TIMEOUT)
        self.assertEqual(niceness(self.viewer_pid), niceness(self.sim_pid) + 10,
                         'the window should run niced 10 below the simulator')
        self.assertTrue(self.sim.world_properties().rendering_enabled)

    def place_car(self, x, y, qz, qw):
        state = ModelState(model_name='racebot', reference_frame='world')
        state.pose.position.x, state.pose.position.y, state.pose.position.z = x, y, 0.1
        state.pose.orientation.z, state.pose.orientation.w = qz, qw
        self.assertTrue(self.set_model_state(state).success)

    def test_2_the_window_shows_the_simulation(self):
        wait_for(self.window_ids, 'a "Bullet Physics" window', START_TIMEOUT)
        self.place_car(*SPAWN_SPOT)
        start = time.time()
        wait_for(lambda: self.car_at_centre(screen_pixels(self.fbdir)) > 0.15,
                 'the window to show the car (blue) at its centre', START_TIMEOUT, period=0.2)
        print('the window showed the car %.1f s after it was placed' % (time.time() - start))
        still, = wait_for(self.still_screen, 'the screen to stay still once the car stands on its wheels '
                         '(less than 2 % of it changing in a second)', 60.0, period=0.2)
        self.place_car(*TURNED_SPOT)
        wait_for(lambda: self.changed_share(still, screen_pixels(self.fbdir)) > 0.2,
                 'the window to show the car moved (more than 20 % of the screen changed)', 30.0, period=0.2)
        time.sleep(1.0)
        self.assertGreater(self.car_at_centre(self.screen('3-car-moved')), 0.15,
                           'the camera followed the car but the car is not there')

    def test_3_closing_the_window_leaves_the_simulation_running(self):
        windows = wait_for(self.window_ids, 'a "Bullet Physics" window', START_TIMEOUT)
        mark = self.rosout.mark()
        result = self.xdotool('windowkill', windows[0])
        self.assertEqual(result.returncode, 0, result.stderr)
        wait_for(lambda: not pid_alive(self.viewer_pid), 'the window process to exit', 30.0)
        wait_for(lambda: not self.window_ids(), 'the window to disappear', 10.0)
        warning = self.rosout.find('window closed', level=Log.WARN, node='/gazebo', since=mark)
        self.assertIn('goes on without a window', warning.msg)
        self.assertTrue(pid_alive(self.sim_pid), 'the simulator died with its window')
        self.sim.assert_serving(self, sim_seconds=1.0)
        self.sim.assert_state_finite(self)
        self.assertFalse(self.sim.world_properties().rendering_enabled)
        self.assertIsNone(self.launch.poll(), 'roslaunch ended with the window')


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'viewer', ViewerTest)

#!/usr/bin/env python3
"""The window (`rosrun gazebo_ros gzclient`, and `rosrun gazebo_ros gazebo`) in a private Xvfb.

viewer.test starts the world server (racebot.launch gui:=false: no window of its own); this node
starts Xvfb (its screen kept in a file: -fbdir) and the windows, and checks what a Gazebo user
relies on:
- gzclient attaches to the running world server: a node /gazebo_gui whose window is a process of its
  own, both niced below the server; the server says a window attached (get_world_properties'
  rendering_enabled is true with or without a window, as gazebo_ros hard-codes it);
- it shows the simulation: the car at the centre, the screen still while the car stands, changing
  when the car is moved (the camera follows it);
- closing the window ends gzclient (exit 0) and leaves the simulation running: /clock goes on, the
  services answer, the server says the window closed. PyBullet's
  window does not take part in WM_DELETE_WINDOW (it sets no WM_PROTOCOLS), so a window manager's
  close button kills its X connection (XKillClient), which is what `xdotool windowkill` does here;
- a second gzclient attaches again and shows the car;
- when the world server goes, gzclient says so and ends (exit 0);
- `gazebo` starts the world server and the window together; closing the window stops both;
- without a display gzclient says why and ends with 0;
- with no window manager (as here) the keyboard window (racebot.launch's keyboard_teleop) does not sit
  under or over the 3D window: it opens beside one that is there, and moves beside one that opens over
  it (racebot.launch starts the keyboard first; the 3D window comes once the world is loaded).
"""
import os
import shutil
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
from robustness_common import ROOT, Process, Rosout, SimProbe, node_pid, pid_alive, wait_for  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, 'tools'))
from bench.common import child_pids  # noqa: E402

WINDOW_MODULE = 'racebot_sim_bridge.window.viewer_process'
KEYBOARD_WINDOW = '^racebot keyboard teleop$'

START_TIMEOUT = 120.0
# Where the car is put (x, y, quaternion z, w): with the camera 1.5 m behind it, nothing in between.
SPAWN_SPOT = (0.0, 0.0, 0.0, 1.0)              # where racebot.launch spawns it
TURNED_SPOT = (0.3, 0.0, 0.2588190, 0.9659258)  # a little ahead, turned 30 degrees left
SCREEN = (1280, 1024)  # PyBullet's window: 1024 x 768; the keyboard's, about 270 x 170, fits below it
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
        cls.xvfb, cls.display = start_xvfb(fbdir=cls.fbdir, screen='%dx%dx24' % SCREEN)
        cls.env = dict(os.environ, DISPLAY=cls.display)
        rospy.init_node('viewer_test', anonymous=True)
        cls.rosout = Rosout()
        cls.sim = SimProbe()
        cls.sim.wait_ready(START_TIMEOUT)
        rospy.wait_for_service('/gazebo/set_model_state', START_TIMEOUT)
        cls.set_model_state = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)
        wait_for(lambda: 'racebot' in cls.sim.world_properties().model_names, 'the car spawned', START_TIMEOUT)
        cls.sim_pid = wait_for(lambda: node_pid('/gazebo'), "the world server's process id", START_TIMEOUT)
        cls.processes = []
        cls.keyboard = None

    @classmethod
    def tearDownClass(cls):
        for process in cls.processes:
            process.stop()
        stop_xvfb(cls.xvfb)
        shutil.rmtree(cls.fbdir, ignore_errors=True)

    def start(self, executable, *args):
        process = Process(['rosrun', 'gazebo_ros', executable] + list(args), env=self.env)
        self.processes.append(process)
        return process

    def xdotool(self, *args):
        return subprocess.run(['xdotool'] + list(args), env=self.env,
                              capture_output=True, text=True, timeout=20)

    def window_ids(self):
        return self.xdotool('search', '--name', 'Bullet Physics').stdout.split()

    def geometry(self, window):
        """(x, y, width, height) of a window on the screen."""
        out = self.xdotool('getwindowgeometry', '--shell', window).stdout
        geometry = dict(line.split('=', 1) for line in out.split())
        return tuple(int(geometry[key]) for key in ('X', 'Y', 'WIDTH', 'HEIGHT'))

    def start_keyboard(self):
        """racebot.launch's keyboard node on this display (the one before it stopped) -> its window."""
        if ViewerTest.keyboard is not None:
            ViewerTest.keyboard.stop()
            wait_for(lambda: not self.xdotool('search', '--name', KEYBOARD_WINDOW).stdout.split(),
                     'the keyboard window to go', 30.0)
        ViewerTest.keyboard = Process(['rosrun', 'racebot_gazebo', 'keyboard_teleop.py'], env=self.env)
        self.processes.append(ViewerTest.keyboard)
        return wait_for(lambda: self.xdotool('search', '--onlyvisible', '--name', KEYBOARD_WINDOW).stdout.split(),
                        'the keyboard window on %s' % self.display, START_TIMEOUT)[0]

    def assert_keyboard_beside_the_3d_window(self, keyboard, timeout):
        """The keyboard window apart from the 3D window (within `timeout` s) and wholly on the screen."""
        def rectangles():
            return self.geometry(keyboard), self.geometry(self.window_ids()[0])

        def apart():
            (kx, ky, kw, kh), (wx, wy, ww, wh) = rectangles()
            return kx >= wx + ww or ky >= wy + wh or kx + kw <= wx or ky + kh <= wy
        deadline = time.time() + timeout
        while not apart() and time.time() < deadline:
            time.sleep(0.1)
        (kx, ky, kw, kh), three_d = rectangles()
        self.assertTrue(apart(), 'the keyboard window %s overlaps the 3D window %s (x, y, width, height)'
                        % ((kx, ky, kw, kh), three_d))
        self.assertTrue(0 <= kx and kx + kw <= SCREEN[0] and 0 <= ky and ky + kh <= SCREEN[1],
                        'the keyboard window %s is not wholly on the %d x %d screen' % (((kx, ky, kw, kh),) + SCREEN))

    def wait_window(self):
        ViewerTest.centre = None  # a new window: look its place up again
        return wait_for(self.window_ids, 'a "Bullet Physics" window on %s' % self.display, START_TIMEOUT)

    def close_window(self):
        """What a window manager's close button does to PyBullet's window (see the module doc)."""
        windows = self.window_ids()
        self.assertEqual(len(windows), 1, 'expected one window, found %s' % windows)
        result = self.xdotool('windowkill', windows[0])
        self.assertEqual(result.returncode, 0, result.stderr)

    def attached(self, since):
        """The world server's 'a window attached' message since `since`."""
        return self.rosout.find('a window attached: /gazebo_gui', node='/gazebo', since=since,
                                timeout=START_TIMEOUT)

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
        """(x, y) on the screen of the window's centre; looked up once per window (nothing moves it)."""
        if getattr(ViewerTest, 'centre', None) is None:
            x, y, width, height = self.geometry(self.window_ids()[0])
            ViewerTest.centre = (x + width // 2, y + height // 2)
        return ViewerTest.centre

    def car_at_centre(self, screen):
        """Share of car pixels in the window's central box, where the following camera keeps the car: the
        car is strongly coloured (its chassis orange), the room around it grey and beige."""
        cx, cy = self.window_centre()
        box = screen[cy - 20:cy + 30, cx - 25:cx + 25].astype(np.int16)
        coloured = box.max(axis=2) - box.min(axis=2) > 80
        return float(coloured.mean())

    def wait_car_at_centre(self, what):
        start = time.time()
        wait_for(lambda: self.car_at_centre(screen_pixels(self.fbdir)) > 0.15,
                 'the window to show the car at its centre (%s)' % what, START_TIMEOUT, period=0.2)
        print('%s: the window showed the car %.1f s after asked' % (what, time.time() - start))

    def still_screen(self):
        """(screen,) if it did not change in a second (less than 2 %), else None."""
        first = self.screen('1-car-standing')
        time.sleep(1.0)
        return (first,) if self.changed_share(first, self.screen('2-a-second-later')) < 0.02 else None

    def changed_share(self, a, b):
        return float((np.abs(a.astype(np.int16) - b) > 8).any(axis=2).mean())

    def place_car(self, x, y, qz, qw):
        state = ModelState(model_name='racebot', reference_frame='world')
        state.pose.position.x, state.pose.position.y, state.pose.position.z = x, y, 0.1
        state.pose.orientation.z, state.pose.orientation.w = qz, qw
        self.assertTrue(self.set_model_state(state).success)

    def test_1_gzclient_attaches_to_the_running_world_server_in_a_niced_process(self):
        self.assertTrue(self.sim.world_properties().rendering_enabled,
                        'gazebo_ros answers rendering_enabled true always, no window attached yet included')
        mark = self.rosout.mark()
        ViewerTest.first = self.start('gzclient')
        self.wait_window()
        self.attached(mark)
        pid = wait_for(lambda: node_pid('/gazebo_gui'), 'the node /gazebo_gui', START_TIMEOUT)
        self.assertEqual(pid, self.first.proc.pid, 'the node should be gzclient itself')
        window = [p for p in child_pids(pid) if WINDOW_MODULE in command_line(p)]
        self.assertEqual(len(window), 1, 'gzclient should have one window process, has %s' % window)
        for process, what in ((pid, 'gzclient'), (window[0], 'its window')):
            self.assertEqual(niceness(process), niceness(self.sim_pid) + 10,
                             '%s should run niced 10 below the world server' % what)

    def test_2_the_window_shows_the_simulation(self):
        self.place_car(*SPAWN_SPOT)
        self.wait_car_at_centre('first window')
        still, = wait_for(self.still_screen, 'the screen to stay still once the car stands on its wheels '
                          '(less than 2 % of it changing in a second)', 60.0, period=0.2)
        self.place_car(*TURNED_SPOT)
        wait_for(lambda: self.changed_share(still, screen_pixels(self.fbdir)) > 0.2,
                 'the window to show the car moved (more than 20 % of the screen changed)', 30.0, period=0.2)
        time.sleep(1.0)
        self.assertGreater(self.car_at_centre(self.screen('3-car-moved')), 0.15,
                           'the camera followed the car but the car is not there')

    def test_2b_the_keyboard_window_opens_beside_the_3d_window(self):
        self.assert_keyboard_beside_the_3d_window(self.start_keyboard(), timeout=0)  # from its first sight

    def test_3_closing_the_window_ends_gzclient_and_leaves_the_simulation_running(self):
        mark = self.rosout.mark()
        self.close_window()
        self.assertEqual(self.first.wait_exit(30.0), 0, 'gzclient should end with 0 when its window is closed:\n'
                         + self.first.text[-2000:])
        self.assertIn('the window was closed', self.first.text)
        wait_for(lambda: not self.window_ids(), 'the window to disappear', 10.0)
        warning = self.rosout.find('window /gazebo_gui', 'closed', level=Log.WARN, node='/gazebo', since=mark)
        self.assertIn('goes on without it', warning.msg)
        self.assertTrue(pid_alive(self.sim_pid), 'the world server died with its window')
        self.sim.assert_serving(self, sim_seconds=1.0)
        self.sim.assert_state_finite(self)
        self.assertTrue(self.sim.world_properties().rendering_enabled, 'true without a window too, as upstream')

    def test_4_a_second_gzclient_attaches_again(self):
        keyboard = self.start_keyboard()  # first, as racebot.launch does: no 3D window yet
        mark = self.rosout.mark()
        ViewerTest.second = self.start('gzclient')
        self.wait_window()
        self.attached(mark)
        self.assert_keyboard_beside_the_3d_window(keyboard, timeout=10.0)  # moved within a look or two
        self.place_car(*SPAWN_SPOT)
        self.wait_car_at_centre('second window')

    def test_5_gzclient_ends_when_the_world_server_goes(self):
        result = subprocess.run(['rosnode', 'kill', '/gazebo'], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, timeout=30)
        self.assertEqual(result.returncode, 0, result.stdout)
        self.assertEqual(self.second.wait_exit(30.0), 0, self.second.text[-2000:])
        self.assertIn('the world server /gazebo shut down: the window closes with it', self.second.text)
        wait_for(lambda: not pid_alive(self.sim_pid), 'the world server to exit', 30.0)

    def test_6_gazebo_starts_the_world_server_and_the_window_and_closing_it_stops_both(self):
        mark = self.rosout.mark()
        clock_before = self.sim.clock
        gazebo = self.start('gazebo', 'worlds/empty.world')
        wait_for(lambda: self.sim.clock is not None and self.sim.clock != clock_before and self.sim.clock > 1.0,
                 "the new world server's /clock past 1 s", START_TIMEOUT)
        self.wait_window()
        self.attached(mark)
        self.assertEqual(self.sim.world_properties().model_names, ['ground_plane'])
        self.close_window()
        self.assertEqual(gazebo.wait_exit(60.0), 0, gazebo.text[-3000:])
        self.assertIn('the window closed: stopping the world server', gazebo.text)
        wait_for(lambda: node_pid('/gazebo') is None and node_pid('/gazebo_gui') is None,
                 'both nodes to be gone', 30.0)

    def test_7_without_a_display_gzclient_says_why_and_ends(self):
        env = dict(self.env)
        del env['DISPLAY']
        process = Process(['rosrun', 'gazebo_ros', 'gzclient'], env=env)
        self.processes.append(process)
        self.assertEqual(process.wait_exit(60.0), 0, process.text[-2000:])
        process.reader.join(5)
        self.assertIn('no window: there is no display (DISPLAY is unset)', process.text)
        self.assertNotIn('Traceback', process.text)


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'viewer', ViewerTest)

"""The world server node (our gzserver + gazebo_ros + gzclient): `rosrun racebot_sim_bridge world_server WORLD`.

Command line (as gzserver's, via empty_world.launch): `[-u] [--verbose] [-e ENGINE] [other gzserver
options, ignored] WORLD_FILE`. `-u` starts paused. Private parameters:
  ~gui (bool, false)             PyBullet's window, the camera following the first robot (needs a display)
  ~pub_clock_frequency (Hz, 0)   if > 0, /clock at most this often in sim time (gazebo_ros's
                                 /gazebo/pub_clock_frequency); 0 = every world update, as Gazebo
  ~states_publish_rate (Hz, 100) /gazebo/model_states and link_states in sim time when subscribed
                                 (Gazebo: every update; 0 here means that too)
Pacing is in wall time (this node drives ROS time, so rospy's timers cannot pace it): the world's
real_time_update_rate updates per wall second, or as fast as possible when it is 0.
"""
import math
import os
import sys
import threading
import time

import rospy
from rosgraph_msgs.msg import Clock

from . import sdf_world
from .controllers import RosIO
from .gazebo_services import GazeboServices
from .physics import PhysicsError
from .simulator import Simulator

PAUSED_CLOCK_PERIOD = 0.2  # wall seconds between /clock repeats while paused (late joiners get the time)


class RospyLog(object):
    error = staticmethod(rospy.logerr)
    warn = staticmethod(rospy.logwarn)
    info = staticmethod(rospy.loginfo)


def parse_args(argv):
    """gzserver-style arguments -> (world path or None, paused, verbose, ignored options)."""
    world, paused, verbose, ignored = None, False, False, []
    it = iter(argv)
    for a in it:
        if a in ('-u', '--pause'):
            paused = True
        elif a == '--verbose':
            verbose = True
        elif a in ('-e', '--physics'):
            engine = next(it, 'ode')
            if engine != 'ode':
                ignored.append('-e %s (the physics engine is always PyBullet here)' % engine)
        elif a.startswith('-'):
            ignored.append(a)
        elif a.strip():
            world = a
    return world, paused, verbose, ignored


def resolve_world(name):
    """gzserver looks worlds up in GAZEBO_RESOURCE_PATH; we also look in our own package."""
    if not name:
        name = 'worlds/empty.world'
    if os.path.isabs(name):
        return name
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = [os.path.abspath(name)]
    for root in os.environ.get('GAZEBO_RESOURCE_PATH', '').split(':'):
        if root:
            candidates.append(os.path.join(root, name))
    try:
        import rospkg
        candidates.append(os.path.join(rospkg.RosPack().get_path('racebot_sim_bridge'), name))
    except Exception:  # rospkg missing or package not on ROS_PACKAGE_PATH: fall through to the source tree
        pass
    candidates.append(os.path.join(here, '..', '..', name))
    for c in candidates:
        if os.path.isfile(c):
            return os.path.abspath(c)
    return name  # load_world reports it missing, with the path


def display_available():
    return bool(os.environ.get('DISPLAY'))


class WorldServer(object):
    def __init__(self, world_path, paused, gui):
        spec = sdf_world.load_world(world_path)
        for w in spec.warnings:
            rospy.logwarn('%s: %s' % (os.path.basename(world_path), w))
        ph = spec.physics
        if gui and not display_available():
            rospy.logwarn('gui:=true but there is no display (DISPLAY is unset): running headless')
            gui = False
        try:
            self.sim = Simulator(spec, RosIO(rospy), RospyLog, self._get_param, gui=gui)
        except PhysicsError as err:
            if not gui:
                raise
            rospy.logwarn('could not open the PyBullet window (%s): running headless' % err)
            self.sim = Simulator(spec, RosIO(rospy), RospyLog, self._get_param, gui=False)
        self.sim.paused = paused
        self.update_rate = ph.real_time_update_rate
        self.clock_period = self._rate_param('~pub_clock_frequency', 0.0)
        self.states_period = self._rate_param('~states_publish_rate', 100.0)
        self.clock_pub = rospy.Publisher('/clock', Clock, queue_size=10)
        self.services = GazeboServices(rospy, self.sim)
        self.clock_msg = Clock()
        self.last_clock = -math.inf
        self.last_states = -math.inf
        rospy.loginfo('world %s loaded: %d models, step %g s, %s, %s' % (
            world_path, len(self.sim.model_names()), self.sim.step_size,
            'as fast as possible' if self.update_rate <= 0 else '%g updates/s' % self.update_rate,
            'paused' if paused else 'running'))

    @staticmethod
    def _get_param(path):
        try:
            return rospy.get_param(path)
        except KeyError:
            return None

    @staticmethod
    def _rate_param(name, default):
        rate = rospy.get_param(name, default)
        try:
            rate = float(rate)
        except (TypeError, ValueError):
            rospy.logwarn('%s must be a number of Hz, got %r; using %g' % (name, rate, default))
            rate = default
        return 1.0 / rate if rate > 0 and math.isfinite(rate) else 0.0

    def publish_clock(self, force=False):
        t = self.sim.time
        if not force and self.clock_period and t - self.last_clock < self.clock_period - 1e-9:
            return
        self.last_clock = t
        self.clock_msg.clock = rospy.Time.from_sec(t)
        self.clock_pub.publish(self.clock_msg)

    def run(self):
        self.publish_clock(force=True)
        wall_start, steps_since = time.perf_counter(), 0
        last_paused_clock = 0.0
        follow = self._follow_target()
        while not rospy.is_shutdown():
            if self.sim.paused:
                now = time.perf_counter()
                if now - last_paused_clock >= PAUSED_CLOCK_PERIOD:
                    self.publish_clock(force=True)
                    last_paused_clock = now
                time.sleep(0.002)
                wall_start, steps_since = time.perf_counter(), 0
                continue
            before = self.sim.time
            self.sim.step()
            steps_since += 1
            if self.sim.time < before:  # a reset sent time back: publish it at once
                self.last_clock = self.last_states = -math.inf
            self.publish_clock()
            if self.sim.time - self.last_states >= self.states_period - 1e-9:
                self.last_states = self.sim.time
                self.services.publish_states()
            if follow is not None and self.sim.steps % 33 == 0:
                follow()
            if self.update_rate > 0:
                ahead = wall_start + steps_since / self.update_rate - time.perf_counter()
                if ahead > 0.002:
                    time.sleep(ahead)
                elif ahead < -0.5:  # far behind (a slow machine, a debugger): do not sprint to catch up
                    wall_start, steps_since = time.perf_counter(), 0

    def _follow_target(self):
        if not self.sim.world.gui:
            return None

        def follow():
            robots = list(self.sim.robots.values())
            if robots:
                with self.sim.lock:
                    self.sim.world.follow_with_camera(robots[0].body)
        return follow

    def shutdown(self):
        self.services.shutdown()
        self.sim.close()


def main(argv=None):
    argv = rospy.myargv(argv if argv is not None else sys.argv)[1:]
    rospy.init_node('gazebo', anonymous=False)
    world, paused, verbose, ignored = parse_args(argv)
    for opt in ignored:
        rospy.loginfo('gzserver option %s has no meaning here; ignored' % opt)
    path = resolve_world(world)
    try:
        server = WorldServer(path, paused, bool(rospy.get_param('~gui', False)))
    except (sdf_world.WorldError, PhysicsError) as err:
        rospy.logfatal('could not load world: %s' % err)
        sys.exit(1)
    try:
        server.run()
    finally:  # after the loop, never during a step: the physics client must outlive every step
        server.shutdown()

"""make bench's fleet part (issue 17): 1 to 8 differential-drive robots (every count, issue 30) as fast as possible.

Each robot is the fixture package diffbot_plugins (tests/fixtures/robots): gazebo_plugins' diff drive, a
360-ray laser at 10 Hz and the IMU model plugin at 50 Hz, spawned through gazebo_ros's spawn service in a
namespace of its own (/robot0, /robot1, ...; as `spawn_model -robot_namespace`), in gazebo_ros's
empty_world.launch with real_time_update_rate 0. Every laser and IMU is subscribed (a SLAM node would be)
and every robot driven along a circle. Beside it, in the bench's own process, bare PyBullet steps the same
bodies loaded the same way (physics.PhysicsWorld), with the wheels' velocity motors set to the same speeds
and the same ray casts and IMU reads per robot at the sensors' rates. Ceiling and bridge take turns (the
world paused while the ceiling runs); each figure is the median of the pairs, with its spread.
"""
import os
import subprocess
import time

import numpy as np

from . import common, profiling, stats

FIXTURES = os.path.join(common.REPO, 'tests', 'fixtures', 'robots')
URDF_XACRO = os.path.join(FIXTURES, 'diffbot_plugins', 'urdf', 'diffbot_plugins.urdf.xacro')
WHEEL_SEPARATION = 0.34  # m, the fixture's
WHEEL_RADIUS = 0.075     # m
COMMAND = (0.2, 0.1)     # m/s, rad/s: each robot drives a circle
SPACING = 2.0            # m between the robots (along y)
LASER_PERIOD_S = 0.1     # the fixture's sensor <update_rate> 10
IMU_PERIOD_S = 0.02      # its IMU plugin's updateRate 50
LASER_RAYS = 360
LASER_ANGLES = (-3.14159265, 3.14159265)  # its <min_angle>, <max_angle>
LASER_RANGE = (0.12, 3.5)
LASER_LINK = 'laser_link'


def render_urdf():
    """The fixture's robot_description as its spawn.launch makes it (the xacro executable)."""
    env = dict(os.environ, ROS_PACKAGE_PATH=os.pathsep.join([FIXTURES, os.environ.get('ROS_PACKAGE_PATH', '')]))
    return subprocess.run(['xacro', URDF_XACRO], check=True, capture_output=True, text=True, env=env).stdout


class FleetCeiling:
    """Bare PyBullet: n copies of the robot in the empty world, wheels at the command's speeds, the lasers' and
    IMUs' reads at their rates."""

    def __init__(self, world_file, urdf_xml, n):
        from racebot_sim_bridge.description import sdf_reader, urdf_reader
        from racebot_sim_bridge.engine.physics import PhysicsWorld
        import pybullet as pb
        spec = sdf_reader.load_world(world_file)
        self.step_size = spec.physics.max_step_size
        self.world = PhysicsWorld(self.step_size, spec.physics.gravity)
        self.world.load_world(spec)
        model = urdf_reader.parse_urdf(urdf_xml)
        self.client = self.world.client.id
        self.bodies = []
        v, w = COMMAND
        speeds = ((v - w * WHEEL_SEPARATION / 2) / WHEEL_RADIUS, (v + w * WHEEL_SEPARATION / 2) / WHEEL_RADIUS)
        for k in range(n):
            with common.quiet_stdout():
                body = self.world.spawn_urdf('robot%d' % k, model, urdf_xml, position=(0.0, SPACING * k, 0.02))
            wheels = [body.joints['left_wheel_joint'].index, body.joints['right_wheel_joint'].index]
            pb.setJointMotorControlArray(body.id, wheels, pb.VELOCITY_CONTROL, targetVelocities=speeds,
                                         forces=[10.0, 10.0], physicsClientId=self.client)
            self.bodies.append(body.id)
        # The laser's pose on the body as the sensor has it: PyBullet gives the base's centre of mass, so from it
        # through the inverse of the base's inertial frame to its link frame, then to laser_link. (Taken from the
        # centre of mass, as this bench once did, the rays started 0.6 mm higher: they graze the wheels
        # differently, which cost 2-20 % less than the sensor's own rays from the same pose.)
        link = model.lumped_link(LASER_LINK)
        if link != model.root_link:
            raise common.BenchError('the fixture\'s %s is lumped into %s, not the base' % (LASER_LINK, link))
        inertial = pb.getDynamicsInfo(self.bodies[0], -1, physicsClientId=self.client)[3:5]
        self.laser_offset = pb.multiplyTransforms(*pb.invertTransform(*inertial),
                                                  *model.pose_in_lumped_link(LASER_LINK))
        angles = np.linspace(LASER_ANGLES[0], LASER_ANGLES[1], LASER_RAYS)
        self.directions = np.stack([np.cos(angles), np.sin(angles), np.zeros(LASER_RAYS)], axis=1)
        self.laser_every = max(1, int(round(LASER_PERIOD_S / self.step_size)))
        self.imu_every = max(1, int(round(IMU_PERIOD_S / self.step_size)))
        self.steps = 0

    def run_steps(self, count):
        import pybullet as pb
        client, step = self.client, pb.stepSimulation
        for _ in range(count):
            step(physicsClientId=client)
            self.steps += 1
            if self.steps % self.imu_every == 0:  # the IMU plugin's body: the base's pose and velocity
                for body in self.bodies:
                    pb.getBasePositionAndOrientation(body, physicsClientId=client)
                    pb.getBaseVelocity(body, physicsClientId=client)
            if self.steps % self.laser_every == 0:
                for body in self.bodies:
                    pos, orn = pb.getBasePositionAndOrientation(body, physicsClientId=client)
                    pos, orn = pb.multiplyTransforms(pos, orn, *self.laser_offset)
                    rot = np.array(pb.getMatrixFromQuaternion(orn)).reshape(3, 3)
                    origin = np.array(pos)
                    dirs = self.directions @ rot.T
                    starts, ends = origin + LASER_RANGE[0] * dirs, origin + LASER_RANGE[1] * dirs
                    pb.rayTestBatch(starts.tolist(), ends.tolist(), numThreads=1, physicsClientId=client)

    def measure(self, wall_seconds, chunk=200):
        """Steps for about wall_seconds; returns steps per wall second."""
        return common.steps_per_second(self.run_steps, wall_seconds, chunk)

    def close(self):
        self.world.close()


def _spawn(n, urdf_xml):
    import rospy
    from gazebo_msgs.srv import SpawnModel
    from geometry_msgs.msg import Pose, Twist
    from sensor_msgs.msg import Imu, LaserScan
    rospy.wait_for_service('/gazebo/spawn_urdf_model', 60)
    spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
    counts = {}
    subscribers, publishers = [], []

    def counter(topic):
        counts[topic] = 0

        def cb(_msg):
            counts[topic] += 1
        return cb
    for k in range(n):
        pose = Pose()
        pose.position.y, pose.position.z, pose.orientation.w = SPACING * k, 0.02, 1.0
        res = spawn('robot%d' % k, urdf_xml, '/robot%d' % k, pose, 'world')
        if not res.success:
            raise common.BenchError('spawning robot%d failed: %s' % (k, res.status_message))
        for topic, cls in (('/robot%d/scan' % k, LaserScan), ('/robot%d/imu' % k, Imu)):
            subscribers.append(rospy.Subscriber(topic, cls, counter(topic), queue_size=10))
        pub = rospy.Publisher('/robot%d/cmd_vel' % k, Twist, queue_size=1, latch=True)
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = COMMAND
        pub.publish(cmd)
        publishers.append(pub)
    return counts, subscribers + publishers


def fleet(p, out):
    """The fleet part, one master for all counts: for each count in p['counts'] a fresh world server with that
    many robots, p['rounds'] pairs of p['window_s'] wall seconds each after p['warmup_s']."""
    from .ros_node import WORLD_SERVER, GazeboClient, init_node, measure_window, node_pid
    port = p['port']
    world_file = common.fast_world(common.EMPTY_WORLD, os.path.join(out, 'empty_fast.world'))
    urdf_xml = render_urdf()
    results = {}
    core = common.roscore(port, os.path.join(out, 'logs', 'fleet_roscore.log'))
    try:
        init_node('racebot_bench_fleet')  # before the launch sets /use_sim_time
        for n in p['counts']:
            launch = common.roslaunch(['gazebo_ros', 'empty_world.launch', 'gui:=false', 'world_name:=' + world_file],
                                      port, os.path.join(out, 'logs', 'fleet%d_roslaunch.log' % n))
            keep = []
            try:
                world = GazeboClient()
                counts, keep = _spawn(n, urdf_xml)
                pid = node_pid(WORLD_SERVER, port)
                with common.quiet_stdout():
                    ceiling = FleetCeiling(world_file, urdf_xml, n)
                time.sleep(p['warmup_s'])
                rounds = []
                for k in range(p['rounds']):
                    entry = {}
                    for part in (('ceiling', 'bridge') if k % 2 == 0 else ('bridge', 'ceiling')):
                        if part == 'ceiling':
                            world.pause()
                            time.sleep(0.1)
                            entry['ceiling_rtf'] = ceiling.measure(p['window_s']) * ceiling.step_size
                            world.unpause()
                        else:
                            time.sleep(0.2)
                            entry.update(measure_window(world, pid, p['window_s']))
                    entry['ratio'] = entry['rtf'] / entry['ceiling_rtf']
                    rounds.append(entry)
                ceiling.close()
                profile = None
                if p.get('profile_s') and n == max(p['counts']):  # where the largest fleet's update goes
                    profile = profiling.profile_world_server(pid, p['profile_s'], out, 'fleet%d_world_server' % n)
                if not all(counts.values()):
                    raise common.BenchError('%d robots: topics that got nothing: %s'
                                            % (n, sorted(t for t, c in counts.items() if not c)))
                spread = stats.of_pairs(rounds, ('ceiling_rtf', 'rtf', 'ratio'))
                results[str(n)] = {'robots': n, 'rounds': rounds, 'spread': spread,
                                   'ratio': spread['ratio']['median'], 'bridge_rtf': spread['rtf']['median'],
                                   'ceiling_rtf': spread['ceiling_rtf']['median'], 'messages': dict(counts)}
                if profile is not None:
                    results[str(n)]['profile'] = profile
            finally:
                for handle in keep:
                    handle.unregister()
                launch.stop()
    finally:
        core.stop()
    return results

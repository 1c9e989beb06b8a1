"""A world for the ray-sensor plugins' tests: a real Simulator (PyBullet DIRECT) with the rospy stand-in of
fakes.py (no master), a ground plane and a static wall whose near face is the plane x = WALL_X, from
y = WALL_Y_MIN to 10 and z = 0 to 2, laser_retro WALL_RETRO. A box robot rests at the origin with a sensor link
SENSOR_Z above the ground; the sensor block under test goes on that link. From the sensor, a ray at yaw a and
pitch b that hits the wall's face does so at x = WALL_X, y = WALL_X tan a, z = WALL_X tan b / cos a, range
WALL_X / (cos a cos b): rays at a yaw below about -0.025 rad pass beside the wall."""
import math

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager

from fakes import FakeLog, FakeRospy, NullIO
from sensors_sim import listen, run  # noqa: F401 (run, listen: for the tests)

WALL_X = 2.0
WALL_Y_MIN = -0.05
WALL_RETRO = 200.0
BASE_Z = 0.05      # the base box's centre: 0.1 high, resting on the ground
SENSOR_Z = 0.45    # the sensor link above the ground
WORLD = """<sdf version="1.6"><world name="default">
<model name="ground_plane"><static>true</static><link name="link"><collision name="collision"><geometry>
<plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>
<model name="wall"><static>true</static><pose>{x} {y} 1 0 0 0</pose><link name="link">
<collision name="collision"><laser_retro>{retro}</laser_retro><geometry><box><size>1 {w} 2</size></box></geometry>
</collision></link></model>
</world></sdf>""".format(x=WALL_X + 0.5, y=(WALL_Y_MIN + 10.0) / 2, w=10.0 - WALL_Y_MIN, retro=WALL_RETRO)
ROBOT = """<?xml version="1.0"?>
<robot name="ray_robot">
  <link name="base_link">
    <inertial><mass value="1.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="sensor_link"/>
  <joint name="sensor_joint" type="fixed">
    <parent link="base_link"/><child link="sensor_link"/><origin xyz="0 0 {z}"/>
  </joint>
  <gazebo reference="sensor_link">
    {sensor}
  </gazebo>
</robot>"""


def ray_sensor(name, plugin, horizontal, vertical=None, rate=10, range_min=0.1, range_max=5.0, kind='ray',
               noise=''):
    """A <sensor> block: `horizontal` and `vertical` are (samples, resolution, min angle, max angle)."""
    def axis(tag, values):
        samples, resolution, low, high = values
        return ('<%s><samples>%d</samples><resolution>%g</resolution><min_angle>%r</min_angle>'
                '<max_angle>%r</max_angle></%s>' % (tag, samples, resolution, low, high, tag))
    scan = axis('horizontal', horizontal) + (axis('vertical', vertical) if vertical else '')
    return ('<sensor type="%s" name="%s"><update_rate>%g</update_rate><ray><scan>%s</scan><range><min>%g</min>'
            '<max>%g</max><resolution>0.001</resolution></range>%s</ray>%s</sensor>'
            % (kind, name, rate, scan, range_min, range_max, noise, plugin))


def make_world(tmp_path, sensor, params=None, namespace='/', reconfigure=None):
    """(sim, fake rospy, SensorManager, robot) with the robot carrying `sensor` (a <sensor> block's text)."""
    path = tmp_path / 'wall.world'
    path.write_text(WORLD)
    sim = Simulator(sdf_reader.load_world(str(path)), NullIO(), FakeLog(), lambda path: None)
    fake = FakeRospy(dict({'~sensors/report_period': 0, '~sensors/noise': False, '~sensors/render_worker': False},
                          **(params or {})))
    kwargs = {} if reconfigure is None else {'reconfigure': reconfigure}
    manager = SensorManager(fake, sim, **kwargs)
    robot = sim.spawn_urdf('ray_robot', ROBOT.format(z=SENSOR_Z - BASE_Z, sensor=sensor), namespace,
                           (0.0, 0.0, BASE_Z))
    frame = robot.body.com_pose_for_frame((0.0, 0.0, BASE_Z), (0, 0, 0, 1))
    robot.body.set_pose(frame.position, frame.orientation)
    return sim, fake, manager, robot


def on_wall(yaw, pitch):
    """(x, y, z, range) where a ray at `yaw`, `pitch` from the sensor meets the wall's face."""
    return (WALL_X, WALL_X * math.tan(yaw), WALL_X * math.tan(pitch) / math.cos(yaw),
            WALL_X / (math.cos(yaw) * math.cos(pitch)))


def hits_wall(yaw):
    return WALL_X * math.tan(yaw) > WALL_Y_MIN

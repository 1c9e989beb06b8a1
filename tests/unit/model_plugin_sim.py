"""A real Simulator (PyBullet DIRECT, a ground plane) with the model-plugin manager and a rospy stand-in
(no master): what the unit tests of the drive plugins (test_plugins_*.py) spawn their robots into."""
from pathlib import Path

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY
from racebot_sim_bridge.engine.simulator import Simulator

from fakes import FakeLog, FakeRospy, NullIO

ROBOTS = Path(__file__).resolve().parents[1] / 'fixtures' / 'robots'
GROUND = """<sdf version="1.6"><world name="default">
<model name="ground_plane"><static>true</static><link name="link"><collision name="collision"><geometry>
<plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>
</world></sdf>"""


def fixture_urdf(package):
    """The URDF of a fixture package's xacro (tests/fixtures/robots/<package>/urdf/<package>.urdf.xacro)."""
    import xacro
    # mappings: an argument context, which the xacro:args of a fixture need (their defaults are used)
    return xacro.process_file(str(ROBOTS / package / 'urdf' / ('%s.urdf.xacro' % package)), mappings={}).toxml()


class PluginRospy(FakeRospy):
    """FakeRospy with subscribers (callbacks by topic) and parameters looked up by has_param."""

    def __init__(self, params=None):
        super().__init__(params)
        self.subscribers = {}

    def Subscriber(self, topic, msg_class, callback, queue_size=None):
        assert queue_size, 'every subscriber needs a queue_size'
        self.subscribers[topic] = callback
        return self

    def has_param(self, name):
        return name in self.params

    def unregister(self):
        pass


class Reconfigure:
    """dynamic_reconfigure's Server as the plugins see it, without a master: the first call with level ~0
    (the configuration the callback fills), then change(values) as a set_parameters call (level 1)."""

    def __init__(self, config_type, callback):
        self.config_type, self.callback = config_type, callback
        self.config = callback(dict(config_type.defaults), ~0)

    def change(self, **values):
        self.config = self.callback(dict(self.config, **values), 1)
        return self.config


class PluginWorld:
    def __init__(self, tmp_path, params=None, registry=REGISTRY):
        """`registry`: the plugin classes by library (a test's own plugin class: a Registry of it)."""
        path = tmp_path / 'ground.world'
        path.write_text(GROUND)
        self.sim = Simulator(sdf_reader.load_world(str(path)), NullIO(), FakeLog(), lambda path: None)
        self.fake = PluginRospy(params)
        self.servers = {}  # namespace -> Reconfigure
        self.manager = PluginManager(self.fake, self.sim, registry=registry, reconfigure=self._reconfigure)

    def _reconfigure(self, namespace, config_type, callback):
        server = self.servers[namespace] = Reconfigure(config_type, callback)
        return server

    def spawn(self, name, urdf, namespace='/', pose=(0.0, 0.0, 0.0)):
        """As spawn_urdf_model places a robot: its root link frame at `pose` (x, y, z), level."""
        robot = self.sim.spawn_urdf(name, urdf, namespace, pose)
        frame = robot.body.com_pose_for_frame(pose, (0, 0, 0, 1))
        robot.body.set_pose(frame.position, frame.orientation)
        return robot

    def run(self, seconds):
        for _ in range(int(round(seconds / self.sim.step_size))):
            self.sim.step()

    def warnings(self, text=''):
        return [m for level, m in self.fake.logs if level == 'warn' and text in m]

    def errors(self, text=''):
        return [m for level, m in self.fake.logs if level == 'error' and text in m]

    def close(self):
        self.manager.close()
        self.sim.close()

"""gazebo_ros's services are advertised in the order of gazebo_ros_api_plugin.cpp's advertiseServices():
each is one call to the master, so a client that waited for one (spawn_model waits for spawn_urdf_model, tests
and scripts for get_world_properties) may call it and those before it, and reset_world, the last, means all
are there. Registering them out of that order made a test that waited for get_world_properties find no
set_model_configuration under load."""
from types import SimpleNamespace

import rospy

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_api.services import ADVERTISED, GazeboServices

from fakes import FakeLog
from wheel_robot import EMPTY_WORLD


class _RecordingRospy(SimpleNamespace):
    """rospy, whose Service records the names advertised, in order."""

    def __init__(self):
        super().__init__(advertised=[])

    def __getattr__(self, name):
        return getattr(rospy, name)

    def Service(self, name, cls, handler):  # noqa: N802 (rospy's name)
        self.advertised.append(name)
        return SimpleNamespace(shutdown=lambda: None, cls=cls, handler=handler)


def test_the_services_are_advertised_in_gazebo_ros_order_under_the_namespace():
    sim = Simulator(sdf_reader.parse_world(EMPTY_WORLD), None, FakeLog(), lambda path: None)
    fake = _RecordingRospy()
    services = GazeboServices(fake, sim, '/sim/gazebo')
    try:
        assert fake.advertised == ['/sim/gazebo/' + name for name in ADVERTISED]
        assert fake.advertised[:2] == ['/sim/gazebo/spawn_sdf_model', '/sim/gazebo/spawn_urdf_model']
        assert fake.advertised[-1] == '/sim/gazebo/reset_world'
        assert len(set(ADVERTISED)) == len(ADVERTISED) == 27
        for service in services.services:  # every name has its own handler, a bound method of the API
            assert callable(service.handler) and service.handler.__name__ in ADVERTISED
    finally:
        services.shutdown()
        sim.close()

"""The world file's description (Simulator.spec, an sdf_reader.World) stays what the file said: the property
services change the live state, which lives in the engine (the Simulator's step size, update rate and
lights, the PhysicsWorld's gravity), and read it back from there (issue 28, item 3). Real rospy services
(no master), real PyBullet."""
import copy

import pytest
import rospy
from gazebo_msgs.msg import ODEPhysics
from gazebo_msgs.srv import (DeleteLightRequest, GetLightPropertiesRequest, GetPhysicsPropertiesRequest,
                             SetLightPropertiesRequest, SetPhysicsPropertiesRequest)
from geometry_msgs.msg import Vector3

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_api.properties import GazeboProperties

from fakes import FakeLog


@pytest.fixture
def world():
    sim = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), None, FakeLog(), lambda path: None)
    properties = GazeboProperties(rospy, sim)
    yield sim, properties, copy.deepcopy(sim.spec)
    sim.close()


def test_set_physics_properties_leaves_the_world_description_as_the_file_said(world):
    sim, properties, described = world
    res = properties.set_physics_properties(SetPhysicsPropertiesRequest(
        time_step=0.002, max_update_rate=250.0, gravity=Vector3(0.0, 0.0, -1.62), ode_config=ODEPhysics()))
    assert res.success, res.status_message
    got = properties.get_physics_properties(GetPhysicsPropertiesRequest())
    assert (got.time_step, got.max_update_rate) == (0.002, 250.0)
    assert (got.gravity.x, got.gravity.y, got.gravity.z) == pytest.approx((0.0, 0.0, -1.62))
    assert (sim.step_size, sim.real_time_update_rate) == (0.002, 250.0)  # the engine holds what is live
    assert sim.spec == described
    assert (sim.spec.physics.max_step_size, sim.spec.physics.real_time_update_rate) == (0.001, 1000.0)


def test_the_light_services_leave_the_world_description_as_the_file_said(world):
    sim, properties, described = world
    res = properties.set_light_properties(SetLightPropertiesRequest(light_name='sun', attenuation_constant=0.5))
    assert res.success
    assert properties.get_light_properties(GetLightPropertiesRequest(light_name='sun')).attenuation_constant == 0.5
    assert properties.delete_light(DeleteLightRequest(light_name='sun')).success
    assert not properties.get_light_properties(GetLightPropertiesRequest(light_name='sun')).success
    assert sim.lights == [] and sim.spec == described and [light.name for light in sim.spec.lights] == ['sun']

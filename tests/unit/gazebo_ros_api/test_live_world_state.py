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


TB3_PHYSICS = """<?xml version="1.0"?>
<sdf version="1.6"><world name="default">
  <physics type="ode">
    <real_time_update_rate>1000.0</real_time_update_rate><max_step_size>0.001</max_step_size>
    <max_contacts>10</max_contacts>
    <ode>
      <solver><type>quick</type><iters>150</iters><precon_iters>0</precon_iters><sor>1.400000</sor></solver>
      <constraints><cfm>0.00001</cfm><erp>0.2</erp><contact_max_correcting_vel>2000.000000</contact_max_correcting_vel>
        <contact_surface_layer>0.01000</contact_surface_layer></constraints>
    </ode>
  </physics>
</world></sdf>"""


def test_get_physics_properties_reports_the_world_files_ode_settings_and_the_engine_takes_its_iterations():
    """turtlebot3_gazebo's worlds set 150 iterations, SOR 1.4, CFM 1e-5, a correcting velocity of 2000: Gazebo's
    ODEPhysics reports what the file says (racebot reported its defaults), and the solver iterates as often."""
    sim = Simulator(sdf_reader.parse_world(TB3_PHYSICS), None, FakeLog(), lambda path: None)
    try:
        ode = GazeboProperties(rospy, sim).get_physics_properties(GetPhysicsPropertiesRequest()).ode_config
        assert (ode.sor_pgs_iters, ode.sor_pgs_precon_iters, ode.sor_pgs_w, ode.cfm, ode.erp,
                ode.contact_max_correcting_vel, ode.contact_surface_layer, ode.max_contacts) == \
            (150, 0, 1.4, 0.00001, 0.2, 2000.0, 0.01, 10)
        assert sim.world.client.getPhysicsEngineParameters()['numSolverIterations'] == 150
    finally:
        sim.close()


def test_a_world_without_ode_settings_reports_sdformats_defaults(world):
    sim, properties, _ = world
    ode = properties.get_physics_properties(GetPhysicsPropertiesRequest()).ode_config
    assert (ode.sor_pgs_iters, ode.sor_pgs_precon_iters, ode.sor_pgs_w, ode.cfm, ode.erp,
            ode.contact_max_correcting_vel, ode.contact_surface_layer, ode.max_contacts) == \
        (50, 0, 1.3, 0.0, 0.2, 100.0, 0.001, 20)
    assert sim.world.client.getPhysicsEngineParameters()['numSolverIterations'] == 50

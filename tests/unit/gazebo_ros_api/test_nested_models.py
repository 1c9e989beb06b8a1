"""Nested models through gazebo_ros's API (issue 29, item 3): as in Gazebo 11, the outer model is the model
(get_world_properties, model_states) and its nested links are outer::inner::link (get_link_state, link_states,
get_model_properties), posed through every level. A world whose models hold <include>s of a model library and a
nested <model>, loaded into a Simulator; the services with real rospy (no master), real PyBullet."""
import math

import pytest
import rospy
from gazebo_msgs.srv import (GetLinkStateRequest, GetModelPropertiesRequest, GetModelStateRequest,
                             GetWorldPropertiesRequest)

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_api.services import GazeboServices
from racebot_sim_bridge.kinematics.rotations import quaternion_to_rpy

from fakes import FakeLog
from sdf_models import ROOM, TABLE, WHEEL, write_model

CART = """
  <model name="cart">
    <pose>0 5 0.2 0 0 0</pose>
    <link name="chassis">
      <inertial><mass>2</mass></inertial>
      <collision name="c"><geometry><box><size>1 0.5 0.1</size></box></geometry></collision>
    </link>
    <include>
      <uri>model://wheel</uri>
      <name>front</name>
      <pose>0.5 0 0 0 0 1.5707963267948966</pose>
    </include>
    <joint name="axle" type="revolute">
      <parent>chassis</parent>
      <child>front::rim</child>
      <axis><xyz>0 0 1</xyz></axis>
    </joint>
  </model>
"""


@pytest.fixture
def services(tmp_path, monkeypatch):
    models = tmp_path / 'models'
    write_model(models, 'table', TABLE)
    write_model(models, 'wheel', WHEEL)
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(models))
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    spec = sdf_reader.parse_world(ROOM.replace('</world>', CART + '</world>'))
    assert spec.warnings == []
    sim = Simulator(spec, None, FakeLog(), lambda path: None)
    sim.spawn_world_robots()  # the cart: joints, so the URDF path
    api = GazeboServices(rospy, sim, '/gazebo')
    yield api
    api.shutdown()
    sim.close()


def link_state(api, name):
    res = api.get_link_state(GetLinkStateRequest(link_name=name, reference_frame='world'))
    assert res.success, (name, res.status_message)
    p, q = res.link_state.pose.position, res.link_state.pose.orientation
    return (p.x, p.y, p.z), quaternion_to_rpy((q.x, q.y, q.z, q.w))


def test_the_outer_models_are_the_worlds_models(services):
    assert services.get_world_properties(GetWorldPropertiesRequest()).model_names == ['ground_plane', 'room', 'cart']
    models, _ = services.states(want_links=False)
    assert models.name == ['ground_plane', 'room', 'cart']
    res = services.get_model_state(GetModelStateRequest(model_name='room'))
    assert (res.pose.position.x, res.pose.position.y) == pytest.approx((10.0, 0.0))
    assert not services.get_model_state(GetModelStateRequest(model_name='shelf')).success


def test_nested_links_answer_by_their_scoped_names_with_poses_composed_through_every_level(services):
    # room (10, 0) turned 90 degrees -> shelf (0, 2) -> box (0.2, 0) turned 90 degrees -> link (0.1, 0, 1.1)
    xyz, rpy = link_state(services, 'room::shelf::box::link')
    assert xyz == pytest.approx((7.9, 0.2, 1.1), abs=1e-6)
    assert abs(rpy[2]) == pytest.approx(math.pi, abs=1e-6)
    xyz, rpy = link_state(services, 'room::table_b::link')  # an included table, at the include's pose
    assert xyz == pytest.approx((10.0, -1.0, 0.5), abs=1e-6) and rpy[2] == pytest.approx(math.pi, abs=1e-6)
    xyz, _ = link_state(services, 'cart::front::hub')  # an included wheel of a robot, through the URDF path
    assert xyz == pytest.approx((0.5, 5.0, 0.25), abs=1e-6)


def test_link_states_and_model_properties_name_the_nested_links(services):
    _, links = services.states(want_models=False)
    for name in ('room::floor', 'room::table_a::link', 'room::table_b::link', 'room::shelf::board',
                 'room::shelf::box::link', 'cart::chassis', 'cart::front::rim', 'cart::front::hub'):
        assert name in links.name
    assert len(links.name) == len(set(links.name)) == 9  # and the ground plane's link
    res = services.properties.get_model_properties(GetModelPropertiesRequest(model_name='cart'))
    assert sorted(res.body_names) == ['chassis', 'front::hub', 'front::rim']
    assert sorted(res.joint_names) == ['axle', 'front::spin']
    room = services.properties.get_model_properties(GetModelPropertiesRequest(model_name='room'))
    assert room.is_static and room.body_names[0] == 'floor'

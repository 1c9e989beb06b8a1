"""Gazebo's loader rules (issue 37 item 4) as gazebo_ros shows them: a model whose mesh is missing, and one whose
link has no collision and no visual, are kept by Gazebo 11 and listed by get_world_properties, answered by
get_model_state; a URDF with <gazebo><static>true</static></gazebo> is a static model (get_model_properties
is_static) that holds still. A Simulator with real rospy (no master) and real PyBullet."""
import pytest
import rospy
from gazebo_msgs.srv import (GetModelPropertiesRequest, GetModelStateRequest, GetWorldPropertiesRequest,
                             SpawnModelRequest)
from geometry_msgs.msg import Pose, Point, Quaternion

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_api.services import GazeboServices

from fakes import FakeLog

WORLD = ('<sdf version="1.6"><world name="w">'
         '<model name="ground_plane"><static>true</static><link name="link"/></model>'  # written without shapes
         '<model name="lamp"><static>true</static><link name="link"><collision name="c"><geometry><mesh>'
         '<uri>file:///nowhere/lamp.dae</uri></mesh></geometry></collision></link></model></world></sdf>')


@pytest.fixture
def services(tmp_path, monkeypatch):
    monkeypatch.setenv('RACEBOT_MESH_CACHE', str(tmp_path / 'cache'))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', '')
    log = FakeLog()
    sim = Simulator(sdf_reader.parse_world(WORLD), None, log, lambda path: None)
    api = GazeboServices(rospy, sim, '/gazebo')
    api.log = log
    yield api
    api.shutdown()
    sim.close()


def spawn(api, service, name, xml, z=0.0):
    return service(SpawnModelRequest(model_name=name, model_xml=xml, robot_namespace='',
                                     initial_pose=Pose(Point(0, 0, z), Quaternion(0, 0, 0, 1)), reference_frame=''))


def test_a_model_with_a_missing_mesh_and_one_without_shapes_are_listed_and_answer(services):
    assert services.get_world_properties(GetWorldPropertiesRequest()).model_names == ['ground_plane', 'lamp']
    for name in ('ground_plane', 'lamp'):
        assert services.get_model_state(GetModelStateRequest(model_name=name)).success
    assert not any('skipped' in w for w in services.log.warnings), services.log.warnings


def test_spawned_models_without_shapes_are_listed(services):
    res = spawn(services, services.spawn_sdf_model, 'bare', '<sdf version="1.6"><model name="bare"><link name="l">'
                '<inertial><mass>2</mass></inertial></link></model></sdf>', z=1.0)
    assert res.success, res.status_message
    urdf = ('<robot name="r"><link name="base"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" '
            'iyy="0.1" iyz="0" izz="0.1"/></inertial></link></robot>')
    res = spawn(services, services.spawn_urdf_model, 'inertial_only', urdf, z=1.0)
    assert res.success, res.status_message
    assert services.get_world_properties(GetWorldPropertiesRequest()).model_names[-2:] == ['bare', 'inertial_only']


def test_a_static_urdf_is_a_static_model_that_holds_still(services):
    urdf = ('<robot name="building"><link name="walls"><inertial><mass value="500"/><inertia ixx="100" ixy="0" '
            'ixz="0" iyy="100" iyz="0" izz="100"/></inertial><collision><geometry><box size="4 4 3"/></geometry>'
            '</collision></link><gazebo><static>true</static></gazebo></robot>')
    assert spawn(services, services.spawn_urdf_model, 'building', urdf, z=3.0).success
    assert services.get_model_properties(GetModelPropertiesRequest(model_name='building')).is_static
    sim = services.sim
    for _ in range(300):
        sim.step()
    state = services.get_model_state(GetModelStateRequest(model_name='building'))
    assert state.pose.position.z == pytest.approx(3.0)

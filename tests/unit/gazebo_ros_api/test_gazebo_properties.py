"""The pure parts of the property services (gazebo_properties), the world's lights (sdf_reader) and the
performance_metrics arithmetic (performance_metrics). No master."""
import math

import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.gazebo_ros_api.link_properties import principal_in_frame, tensor_from_principal
from racebot_sim_bridge.gazebo_ros_api.model_properties import urdf_geom_names
from racebot_sim_bridge.gazebo_ros_api.performance_metrics import NO_FPS, MetricsWindow
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion


# -- inertia --------------------------------------------------------------------------------------
def test_principal_axes_aligned_with_the_link_give_a_diagonal_tensor():
    assert tensor_from_principal((1.0, 2.0, 3.0), (0, 0, 0, 1)) == pytest.approx((1, 0, 0, 2, 0, 3))


def test_turned_principal_axes_give_products_of_inertia():
    # principal moments 1 (x') and 3 (y') with x' at 45 degrees in the xy plane
    ixx, ixy, ixz, iyy, iyz, izz = tensor_from_principal((1.0, 3.0, 5.0), rpy_to_quaternion(0, 0, math.pi / 4))
    assert (ixx, iyy, izz) == pytest.approx((2.0, 2.0, 5.0))
    assert ixy == pytest.approx(-1.0)
    assert (ixz, iyz) == pytest.approx((0.0, 0.0), abs=1e-12)


@pytest.mark.parametrize('q', [(0, 0, 0, 1), rpy_to_quaternion(0.3, -0.7, 2.0)])
def test_a_tensor_round_trips_through_its_principal_frame(q):
    tensor = tensor_from_principal((0.5, 0.7, 0.9), q)
    diagonal, off = principal_in_frame(tensor, q)
    assert diagonal == pytest.approx((0.5, 0.7, 0.9))
    assert off < 1e-12


def test_a_tensor_not_diagonal_in_the_frame_is_measured():
    _, off = principal_in_frame((1.0, 0.5, 0.0, 1.0, 0.0, 1.0), (0, 0, 0, 1))
    assert off == pytest.approx(0.5)


# -- Gazebo's collision names after lumping ---------------------------------------------------------
LUMPED = """<robot name="r">
  <link name="base"><collision><geometry><box size="1 1 1"/></geometry></collision>
    <collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="plate"><collision><geometry><box size="1 1 0.1"/></geometry></collision></link>
  <link name="wheel"><collision><geometry><sphere radius="0.2"/></geometry></collision></link>
  <joint name="fix" type="fixed"><parent link="base"/><child link="plate"/></joint>
  <joint name="spin" type="continuous"><parent link="base"/><child link="wheel"/></joint>
</robot>"""


def test_collision_names_as_sdformat_gives_them():
    model = urdf_reader.parse_urdf(LUMPED)
    assert urdf_geom_names(model, 'base') == ['base_collision', 'base_collision_1',
                                              'base_fixed_joint_lump__plate_collision_2']
    assert urdf_geom_names(model, 'wheel') == ['wheel_collision']


# -- lights -----------------------------------------------------------------------------------------
def test_the_empty_worlds_sun_is_gazebos():
    (sun,) = sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF).lights
    assert (sun.name, sun.type, sun.cast_shadows) == ('sun', 'directional', True)
    assert sun.diffuse == (0.8, 0.8, 0.8, 1.0) and sun.attenuation == (1000.0, 0.9, 0.01, 0.001)
    assert sun.direction == (-0.5, 0.1, -0.9) and sun.pose == (0.0, 0.0, 10.0, 0.0, 0.0, 0.0)


def test_world_lights_are_read_with_sdf_defaults():
    world = sdf_reader.parse_world("""<sdf version="1.6"><world name="w">
      <include><uri>model://sun</uri><name>sun2</name><pose>1 2 3 0 0 0</pose></include>
      <light name="lamp" type="point"><pose>0 0 2 0 0 0</pose><diffuse>0.5 0.4 0.3 1</diffuse>
        <attenuation><range>20</range><linear>0.2</linear></attenuation></light>
      <light name="bad"><diffuse>red</diffuse></light>
    </world></sdf>""")
    assert [light.name for light in world.lights] == ['sun2', 'lamp']
    assert world.lights[0].pose == (1.0, 2.0, 3.0, 0.0, 0.0, 0.0)
    lamp = world.lights[1]
    assert lamp.diffuse == (0.5, 0.4, 0.3, 1.0) and lamp.specular == (0.1, 0.1, 0.1, 1.0)
    assert lamp.attenuation == (20.0, 1.0, 0.2, 0.0) and lamp.direction == (0.0, 0.0, -1.0)
    assert any("light 'bad'" in w for w in world.warnings)


# -- performance metrics --------------------------------------------------------------------------
def test_metrics_rates_over_the_interval():
    window = MetricsWindow()
    assert window.sample(1.0, 10.0, [('w::m::l::laser', 5, False), ('w::m::l::cam', 2, True)]) is None
    rtf, sensors = window.sample(2.0, 12.0, [('w::m::l::laser', 45, False), ('w::m::l::cam', 32, True)])
    assert rtf == pytest.approx(0.5)
    assert sensors == [('w::m::l::cam', pytest.approx(30.0), pytest.approx(15.0), pytest.approx(15.0)),
                       ('w::m::l::laser', pytest.approx(40.0), pytest.approx(20.0), NO_FPS)]


def test_metrics_say_nothing_while_paused_and_keep_quiet_sensors_rates():
    window = MetricsWindow()
    window.sample(0.0, 0.0, [('a', 0, False)])
    window.sample(1.0, 1.0, [('a', 10, False)])
    assert window.sample(1.0, 5.0, [('a', 10, False)]) is None  # no sim time passed
    rtf, sensors = window.sample(2.0, 6.0, [('a', 10, False)])  # a did not measure: its last rates stay
    assert rtf == pytest.approx(0.2)
    assert sensors == [('a', pytest.approx(10.0), pytest.approx(10.0), NO_FPS)]
    assert window.sample(3.0, 7.0, [])[1] == []  # a sensor that is gone is dropped

"""A wheel's friction along the wheel where its <fdir1> says so (engine/wheel_friction.py, bullet_urdf.wheel_axes).

The report (issue 39): AgileX hunter, an Ackermann car whose RobotHWSim sets all four wheels to one rate, turned at
78 % of its steering's rate, and the rate swung with the heading. Here the car is written by the test, of hunter's
size and with hunter's friction: every wheel <fdir1> "1 0 0" square to its axle, mu1 0.8 along it, mu2 0.8 across
the front wheels and 10 across the rear ones.
"""
import math

import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.engine.bullet_urdf import WheelAxes, wheel_axes
from racebot_sim_bridge.engine.physics import PhysicsWorld

from test_physics_world import EMPTY_WORLD

RADIUS, WIDTH, WHEELBASE, TRACK = 0.165, 0.1, 0.65, 0.6
STEER, SPEED = 0.3, 0.5


def _wheel(name, parent, xyz, steered, mu2, fdir1):
    out, link = '', parent
    if steered:
        out += ('<link name="%s_hinge"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" '
                'ixz="0" iyz="0"/></inertial></link><joint name="%s_steer" type="revolute"><parent link="%s"/><child '
                'link="%s_hinge"/><origin xyz="%s"/><axis xyz="0 0 1"/><limit lower="-0.7" upper="0.7" effort="100" '
                'velocity="10"/></joint>' % (name, name, parent, name, xyz))
        link, xyz = name + '_hinge', '0 0 0'
    return out + ('<link name="%s"><inertial><mass value="2"/><inertia ixx="0.02" iyy="0.03" izz="0.02" ixy="0" '
                  'ixz="0" iyz="0"/></inertial><collision><origin rpy="1.5707963 0 0"/><geometry><cylinder radius="%g" '
                  'length="%g"/></geometry></collision></link><joint name="%s_axle" type="continuous"><parent '
                  'link="%s"/><child link="%s"/><origin xyz="%s"/><axis xyz="0 1 0"/></joint><gazebo reference="%s">'
                  '<mu1>0.8</mu1><mu2>%g</mu2>%s</gazebo>'
                  % (name, RADIUS, WIDTH, name, link, name, xyz, name, mu2, '<fdir1>1 0 0</fdir1>' if fdir1 else ''))


def car(fdir1=True):
    """A 30 kg car: a 20 kg box on two steered front wheels and two rear ones."""
    x, y = WHEELBASE / 2, TRACK / 2
    return ('<robot name="car"><link name="base"><inertial><mass value="20"/><inertia ixx="0.5" iyy="1" izz="1.2" '
            'ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><box size="0.8 0.5 0.15"/></geometry>'
            '</collision></link>%s%s%s%s</robot>'
            % (_wheel('fl', 'base', '%g %g 0' % (x, y), True, 0.8, fdir1),
               _wheel('fr', 'base', '%g %g 0' % (x, -y), True, 0.8, fdir1),
               _wheel('rl', 'base', '%g %g 0' % (-x, y), False, 10.0, fdir1),
               _wheel('rr', 'base', '%g %g 0' % (-x, -y), False, 10.0, fdir1)))


@pytest.fixture
def world():
    w = PhysicsWorld(step_size=0.001, gravity=(0.0, 0.0, -9.8))
    w.load_world(sdf_reader.load_world(str(EMPTY_WORLD)))
    yield w
    w.close()


def spawn(world, xml, heading=0.0):
    return world.spawn_urdf('car', urdf_reader.parse_urdf(xml), xml, position=(0, 0, RADIUS + 0.01),
                            orientation=(0, 0, math.sin(heading / 2), math.cos(heading / 2)))


def turn(world, body, seconds=5.0):
    """The mean yaw rate and speed after the first second of a left turn with the hinges at Ackermann's angles for
    STEER and every wheel set to SPEED / RADIUS each step (as hunter's RobotHWSim sets them: Joint::SetVelocity)."""
    client, joints = world.client, {n: j.index for n, j in body.joints.items()}
    t = math.tan(STEER)
    hinges = {'fl_steer': math.atan2(2 * WHEELBASE * t, 2 * WHEELBASE - TRACK * t),
              'fr_steer': math.atan2(2 * WHEELBASE * t, 2 * WHEELBASE + TRACK * t)}
    rates, speeds = [], []
    for k in range(int(seconds * 1000)):
        for name, angle in hinges.items():
            client.resetJointState(body.id, joints[name], angle, 0.0)
        for name in ('fl_axle', 'fr_axle', 'rl_axle', 'rr_axle'):
            joint = body.joints[name]
            joint.set_position(joint.state().position, SPEED / RADIUS)
        world.step()
        if k >= 1000 and k % 50 == 0:
            lin, ang = client.getBaseVelocity(body.id)
            rates.append(ang[2])
            speeds.append(math.hypot(lin[0], lin[1]))
    return sum(rates) / len(rates), sum(speeds) / len(speeds)


def bicycle(speed):
    return speed * math.tan(STEER) / WHEELBASE


def test_wheel_axes_follow_fdir1_square_to_the_axle_or_along_it():
    model = urdf_reader.parse_urdf(car())
    assert wheel_axes(model, 'rl') == WheelAxes(0.8, 10.0, (0.0, 1.0, 0.0))  # fdir1 square to the axle: rolling
    along = urdf_reader.parse_urdf(car().replace('<fdir1>1 0 0</fdir1>', '<fdir1>0 0 1</fdir1>'))
    # "0 0 1" in the collision's frame, which is turned a quarter about x: along the axle, so mu1 is the axle's
    assert wheel_axes(along, 'rl') == WheelAxes(10.0, 0.8, (0.0, 1.0, 0.0))
    oblique = urdf_reader.parse_urdf(car().replace('<fdir1>1 0 0</fdir1>', '<fdir1>1 0 1</fdir1>'))
    assert wheel_axes(oblique, 'rl') is None
    assert wheel_axes(urdf_reader.parse_urdf(car(fdir1=False)), 'rl') is None
    assert wheel_axes(model, 'base') is None  # no continuous joint


@pytest.mark.parametrize('heading', [0.0, math.pi / 4])
def test_the_car_turns_at_its_steering_rate_whatever_its_heading(world, heading):
    rate, speed = turn(world, spawn(world, car(), heading))
    assert rate == pytest.approx(bicycle(SPEED), rel=0.06), (rate, speed)


def test_the_turn_is_the_same_along_a_world_axis_and_at_45_degrees(world):
    along, _ = turn(world, spawn(world, car(), 0.0), seconds=3.0)
    world.remove('car')
    across, _ = turn(world, spawn(world, car(), math.pi / 4), seconds=3.0)
    assert across == pytest.approx(along, rel=0.01)


def test_without_fdir1_bullets_world_fixed_friction_turns_it_short(world):
    # what racebot did before, and still does for a wheel without <fdir1> (ODE's rows then come from the normal
    # alone too)
    rate, speed = turn(world, spawn(world, car(fdir1=False)))
    assert rate < 0.85 * bicycle(SPEED)


def test_a_car_parked_across_a_slope_stays(world):
    # gravity tilted 15 degrees towards -y: the axle's friction (mu 0.8 and 10) holds it; the wheels held at rest
    world.set_gravity((0.0, -9.8 * math.sin(0.26), -9.8 * math.cos(0.26)))
    body = spawn(world, car())
    client = world.client
    wheels = [body.joints[name] for name in ('fl_axle', 'fr_axle', 'rl_axle', 'rr_axle')]

    def step(n):
        for _ in range(n):
            for joint in wheels:
                joint.set_position(joint.state().position, 0.0)
            world.step()
    step(1000)
    start = client.getBasePositionAndOrientation(body.id)[0]
    step(2000)
    end = client.getBasePositionAndOrientation(body.id)[0]
    assert body.wheel_friction.active == {j.index for j in wheels}
    assert math.dist(start, end) < 1e-3


def test_a_wheel_turned_by_effort_keeps_bullets_friction(world):
    body = spawn(world, car())
    client, wheel = world.client, body.joints['rl_axle']
    mu = client.getDynamicsInfo(body.id, wheel.index)[1]
    wheel.set_position(0.0, 1.0)
    world.step()
    assert body.wheel_friction.active == {wheel.index}
    assert client.getDynamicsInfo(body.id, wheel.index)[1] == 0.0  # ODE's box is racebot's now
    wheel.apply_effort(0.5)
    world.step()
    assert body.wheel_friction.active == set()
    assert client.getDynamicsInfo(body.id, wheel.index)[1] == mu


def test_a_reset_forgets_the_held_friction(world):
    body = spawn(world, car())
    turn(world, body, seconds=1.5)
    assert any(v.any() for v in body.wheel_friction.impulse.values())
    world.reset()
    assert not any(v.any() for v in body.wheel_friction.impulse.values())

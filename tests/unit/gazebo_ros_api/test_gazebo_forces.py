"""apply_body_wrench / apply_joint_effort bookkeeping and arithmetic (gazebo_forces), and the wrench
reaching a real PyBullet world through the simulator's before_physics hook. No master."""
import math

import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.gazebo_ros_api.forces import (ForceSchedule, Job, job_due, job_over, shift_wrench,
                                                      start_and_duration, truncate_effort, wrench_in_link)
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion
from racebot_sim_bridge.engine.sim_time import NS as NSEC_PER_SEC
from racebot_sim_bridge.engine.simulator import Simulator

from fakes import FakeLog

MS = 10 ** 6  # ns
IDENTITY = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def approx(v, rel=1e-9, abs_=1e-9):
    return pytest.approx(v, rel=rel, abs=abs_)


# -- job times (ros::Time arithmetic in ns) ---------------------------------------------------------
def test_a_job_runs_from_start_to_start_plus_duration_inclusive():
    job = Job('x', 1.0, 10 * MS, 3 * MS, None)
    assert [job_due(job, t * MS) for t in (9, 10, 11, 13, 14)] == [False, True, True, True, False]
    assert [job_over(job, t * MS) for t in (13, 14)] == [False, True]


def test_a_negative_duration_never_ends():
    job = Job('x', 1.0, 10 * MS, -1 * NSEC_PER_SEC, None)
    assert job_due(job, 10 ** 15) and not job_over(job, 10 ** 15)


def test_a_zero_duration_starting_now_is_never_applied():
    # upstream: start = now, the next update ends one step later, after start + 0
    start, duration = start_and_duration(0, 0, 5 * MS)
    assert (start, duration) == (5 * MS, 0)
    assert not job_due(Job('x', 1, start, duration, None), 6 * MS)


def test_a_start_in_the_past_starts_now():
    assert start_and_duration(1 * MS, 2 * MS, 7 * MS) == (7 * MS, 2 * MS)
    assert start_and_duration(9 * MS, 2 * MS, 7 * MS) == (9 * MS, 2 * MS)


# -- the schedule -------------------------------------------------------------------------------------
def test_a_duration_gives_that_many_steps_of_force():
    schedule = ForceSchedule()
    schedule.add_wrench(('m', 'l'), (1, 0, 0), (0, 0, 0), 0, 5 * MS)
    applied = sum(1 for step in range(1, 20) if schedule.due(step * MS)[0])
    assert applied == 5
    assert schedule.wrenches == []  # dropped once over


def test_the_newest_wrench_on_a_link_wins_and_efforts_add():
    schedule = ForceSchedule()
    schedule.add_wrench(('m', 'l'), (1, 0, 0), (0, 0, 0), 0, -1, 'body')
    schedule.add_wrench(('m', 'l'), (0, 2, 0), (0, 0, 3), 0, -1, 'body')
    schedule.add_wrench(('m', 'k'), (5, 0, 0), (0, 0, 0), 0, -1, 'body')
    schedule.add_effort(('m', 'j'), 1.5, 0, -1, 'body')
    schedule.add_effort(('m', 'j'), 2.0, 0, -1, 'body')
    wrenches, efforts = schedule.due(MS)
    assert wrenches == {('m', 'l'): ((0, 2, 0), (0, 0, 3), 'body'), ('m', 'k'): ((5, 0, 0), (0, 0, 0), 'body')}
    assert sum(e for _, e, _ in efforts) == 3.5


def test_until_cleared_means_until_cleared():
    schedule = ForceSchedule()
    schedule.add_effort(('m', 'j'), 1.0, 0, -1)
    schedule.add_effort(('other', 'k'), 1.0, 0, -1)
    assert all(schedule.due(t * NSEC_PER_SEC)[1] for t in (1, 100, 10000))
    assert schedule.clear_efforts(lambda target: target[1] == 'j') == 1
    assert [target for target, _, _ in schedule.due(10001 * NSEC_PER_SEC)[1]] == [('other', 'k')]


def test_orphans_are_dropped():
    schedule = ForceSchedule()
    schedule.add_wrench(('m', 'l'), (1, 0, 0), (0, 0, 0), 0, -1, 'old body')
    schedule.add_effort(('m', 'j'), 1.0, 0, -1, 'new body')
    schedule.drop_orphans(lambda owner: owner == 'new body')
    assert schedule.wrenches == [] and len(schedule.efforts) == 1


# -- wrench arithmetic --------------------------------------------------------------------------------
def test_a_force_at_a_point_adds_its_moment():
    force, torque = shift_wrench((0, 0, 10), (1, 0, 0), (2, 0, 0))
    assert force == (0, 0, 10)
    assert torque == approx((1, -20, 0))  # r x F = (2,0,0) x (0,0,10) = (0,-20,0)


def test_a_wrench_in_the_links_own_frame_is_unchanged():
    pose = ((1.0, 2.0, 3.0), rpy_to_quaternion(0.3, -0.2, 1.0))
    f, t = wrench_in_link((1, 2, 3), (4, 5, 6), pose, pose)
    assert f == approx((1, 2, 3)) and t == approx((4, 5, 6))


def test_a_wrench_from_an_offset_frame_gains_the_offsets_moment():
    frame = ((0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))  # one metre to the link's left
    f, t = wrench_in_link((1, 0, 0), (0, 0, 0), frame, IDENTITY)
    assert f == approx((1, 0, 0))
    assert t == approx((0, 0, -1))  # (0,1,0) x (1,0,0)


def test_a_wrench_from_a_turned_frame_is_turned_into_the_link():
    frame = ((0.0, 0.0, 0.0), rpy_to_quaternion(0, 0, math.pi / 2))
    link = ((5.0, 5.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    f, t = wrench_in_link((1, 0, 0), (0, 0, 1), frame, link)
    assert f == approx((0, 1, 0))
    # frame origin seen from the link: (-5, -5, 0); torque (0,0,1) + (-5,-5,0) x (0,1,0) = (0, 0, 1 - 5)
    assert t == approx((0, 0, -4))


# -- effort truncation (Joint::CheckAndTruncateForce) --------------------------------------------
@pytest.mark.parametrize('effort, velocity, limits, expected', [
    (5.0, 0.0, (2.0, 1.0), 2.0),      # clamped to the effort limit
    (-5.0, 0.0, (2.0, 1.0), -2.0),
    (1.0, 1.5, (2.0, 1.0), 0.0),      # beyond the velocity limit: no push further
    (-1.0, 1.5, (2.0, 1.0), -1.0),    # braking is allowed
    (1.0, -1.5, (2.0, 1.0), 1.0),
    (7.0, 9.0, (0.0, 0.0), 7.0),      # no limits declared
])
def test_effort_truncation(effort, velocity, limits, expected):
    assert truncate_effort(effort, velocity, *limits) == expected


# -- through a real world -------------------------------------------------------------------------
BOX_WORLD = """<sdf version="1.6"><world name="w">
  <model name="box"><pose>0 0 5 0 0 0</pose><link name="body">
    <inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link></model>
</world></sdf>"""


@pytest.fixture
def box_sim():
    sim = Simulator(sdf_reader.parse_world(BOX_WORLD), io=None, log=FakeLog(), get_params=lambda p: None)
    yield sim
    sim.close()


def _fall(sim, seconds):
    body = sim.body('box')
    z0 = body.pose().position[2]
    for _ in range(int(round(seconds / sim.step_size))):
        sim.step()
    return body.pose().position[2] - z0


def test_m_g_up_through_the_hook_cancels_gravity(box_sim):
    body = box_sim.body('box')
    weight = body.links['body'].dynamics().mass * 9.8
    schedule = ForceSchedule()
    schedule.add_wrench(('box', 'body'), (0, 0, weight), (0, 0, 0), 0, -1, body)

    def apply(t):
        for (_, link), (force, torque, owner) in schedule.due(int(round(t * NSEC_PER_SEC)))[0].items():
            owner.links[link].apply_wrench(force, torque)
    box_sim.before_physics.append(apply)
    assert abs(_fall(box_sim, 0.5)) < 1e-6
    schedule.clear_wrenches(lambda target: True)
    assert _fall(box_sim, 0.2) == approx(-0.5 * 9.8 * 0.2 ** 2, rel=0.02)


def test_changing_the_step_keeps_time_going_on(box_sim):
    for _ in range(10):
        box_sim.step()
    assert box_sim.time == approx(0.01)
    box_sim.set_step_size(0.004)
    box_sim.step()
    assert box_sim.time == approx(0.014)
    assert box_sim.world.step_size == 0.004
    box_sim.reset_simulation()
    box_sim.step()
    assert box_sim.time == approx(0.004)


def test_gravity_change_changes_the_fall(box_sim):
    box_sim.world.set_gravity((0, 0, -2.0))
    assert _fall(box_sim, 0.5) == approx(-0.5 * 2.0 * 0.5 ** 2, rel=0.02)


def test_the_force_jobs_hook_is_called_only_while_there_are_jobs_and_before_the_plugins(box_sim):
    """GazeboForces joins the step hooks with its first job, ahead of those there (gazebo_ros's update runs
    before the model plugins'), pushes the box while the job lasts, and leaves once none is left."""
    from gazebo_msgs.srv import ApplyBodyWrenchRequest
    from racebot_sim_bridge.gazebo_ros_api.forces import GazeboForces
    forces = GazeboForces(FakeLog(), box_sim)
    seen = []

    def plugins(t):
        seen.append(box_sim.before_physics.index(plugins))
    box_sim.set_step_hook('before_physics', plugins, True)
    assert box_sim.before_physics == [plugins]  # nothing to apply: not called at every update
    req = ApplyBodyWrenchRequest(body_name='box::body')
    req.wrench.force.z = 2 * 9.8 * 2  # twice the weight, for 50 ms
    req.duration.nsecs = 50 * MS
    assert forces.apply_body_wrench(req).success
    assert box_sim.before_physics == [forces.apply, plugins]
    rise = _fall(box_sim, 0.05)
    assert rise == approx(0.5 * 9.8 * 0.05 ** 2, rel=0.05)  # up at g while it lasted
    box_sim.step()
    box_sim.step()  # the step after the job ended finds none and leaves
    assert box_sim.before_physics == [plugins] and set(seen) == {0, 1}


def test_gravity_mode_off_hooks_its_weight_back_only_while_some_link_has_it(box_sim):
    from gazebo_msgs.srv import GetLinkPropertiesRequest, SetLinkPropertiesRequest
    from racebot_sim_bridge.gazebo_ros_api.properties import GazeboProperties
    properties = GazeboProperties(FakeLog(), box_sim)
    assert box_sim.before_physics == []
    now = properties.get_link_properties(GetLinkPropertiesRequest(link_name='box::body'))
    req = SetLinkPropertiesRequest(link_name='box::body', com=now.com, gravity_mode=False, mass=now.mass, ixx=now.ixx,
                                   ixy=now.ixy, ixz=now.ixz, iyy=now.iyy, iyz=now.iyz, izz=now.izz)
    assert properties.set_link_properties(req).success
    assert box_sim.before_physics == [properties.links.cancel_gravity]
    assert abs(_fall(box_sim, 0.2)) < 1e-6  # floats
    req.gravity_mode = True
    assert properties.set_link_properties(req).success
    assert _fall(box_sim, 0.2) == approx(-0.5 * 9.8 * 0.2 ** 2, rel=0.02)
    assert box_sim.before_physics == []  # left at the first update with no such link

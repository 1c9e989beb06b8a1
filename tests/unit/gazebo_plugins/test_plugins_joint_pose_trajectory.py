"""gazebo_ros_joint_pose_trajectory on a real Simulator: a two-joint arm whose links gravity would swing. A
trajectory sets the joints point by point (each point's time_from_start added to the previous point's time, as
upstream), with the world's physics off until the update after the last point; a reference link stays put; an
unknown frame_id, a short point and a second trajectory while one plays behave as upstream (or say why not)."""
import math

import pytest
import rospy
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion

from model_plugin_sim import PluginWorld

PLUGIN = '<plugin name="play" filename="libgazebo_ros_joint_pose_trajectory.so">%s</plugin>'
LINK = """<link name="{0}"><inertial><origin xyz="0.25 0 0"/><mass value="1"/>
  <inertia ixx="0.01" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>"""


def arm(params='', fixed=True):
    anchor = '<link name="world"/><joint name="fix" type="fixed"><parent link="world"/><child link="base"/>' \
             '</joint>' if fixed else ''
    return """<robot name="arm">%s
 <link name="base"><inertial><mass value="2"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
 <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 1"/>
  <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="5"/></joint>
 %s
 <joint name="elbow" type="revolute"><parent link="upper"/><child link="tip"/><origin xyz="0.5 0 0"/>
  <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="5"/></joint>
 %s
 <gazebo>%s</gazebo>
</robot>""" % (anchor, LINK.format('upper'), LINK.format('tip'), PLUGIN % params)


def spawn(tmp_path, params='', fixed=True, at=(0.0, 0.0, 0.0)):
    w = PluginWorld(tmp_path)
    robot = w.spawn('arm', arm(params, fixed), '/', at)
    return w, robot


def trajectory(points, names=('shoulder', 'elbow', 'no_such_joint'), frame='world', stamp=0.0):
    msg = JointTrajectory()
    msg.header.frame_id = frame
    msg.header.stamp = rospy.Time.from_sec(stamp)
    msg.joint_names = list(names)
    for positions, after in points:
        msg.points.append(JointTrajectoryPoint(positions=list(positions),
                                               time_from_start=rospy.Duration.from_sec(after)))
    return msg


def angles(w, robot):
    return [s[0] for s in robot.body.joint_states_raw([robot.body.joints[n].index
                                                                     for n in ('shoulder', 'elbow')])]


def test_points_play_at_the_summed_times_with_physics_off(tmp_path):
    w, robot = spawn(tmp_path)
    try:
        assert set(w.fake.subscribers) == {'/set_joint_trajectory'} and not w.warnings() and not w.errors()
        w.fake.subscribers['/set_joint_trajectory'](trajectory([((0.5, -0.3, 9.0), 1.0), ((1.0, 0.2, 9.0), 2.0)]))
        w.run(0.001)  # taken and started at the first update (its stamp 0 is in the past)
        assert angles(w, robot) == pytest.approx([0.5, -0.3], abs=1e-9) and w.sim.physics_enabled is False
        w.run(0.999)  # physics off: gravity does not swing the arm, time goes on
        assert angles(w, robot) == pytest.approx([0.5, -0.3], abs=1e-9) and w.sim.time == pytest.approx(1.0)
        w.run(0.001)  # start + 1 s
        assert angles(w, robot) == pytest.approx([1.0, 0.2], abs=1e-9)
        w.run(1.999)  # the next update is at 1.001 + 2 s (time_from_start added to the previous point's time)
        assert angles(w, robot) == pytest.approx([1.0, 0.2], abs=1e-9) and w.sim.physics_enabled is False
        w.run(0.001)
        assert w.sim.physics_enabled is True
        w.run(0.3)
        assert abs(angles(w, robot)[0] - 1.0) > 0.05  # physics back: the arm swings under gravity
        played = [m for level, m in w.fake.logs if level == 'info' and 'updating configuration' in m]
        assert len(played) == 2 and '[0/2]' in played[0] and '[1/2]' in played[1]
    finally:
        w.close()


def test_a_future_stamp_waits_and_a_reference_link_stays_put(tmp_path):
    w, robot = spawn(tmp_path, fixed=False, at=(0.0, 0.0, 2.0))  # in the air; physics off keeps it there
    try:
        w.fake.subscribers['/set_joint_trajectory'](trajectory([((0.8, 0.4), 0.5)], names=('shoulder', 'elbow'),
                                                               frame='tip', stamp=0.2))
        w.run(0.1)
        assert angles(w, robot) == pytest.approx([0.0, 0.0], abs=1e-6)  # not before its stamp
        tip_before = link_motion(w.sim.world, robot.body, 'tip')[:2]
        base_before = robot.body.frame_pose().position
        w.run(0.1)
        assert angles(w, robot) == pytest.approx([0.8, 0.4], abs=1e-9)
        tip_after = link_motion(w.sim.world, robot.body, 'tip')[:2]
        assert tip_after[0] == pytest.approx(tip_before[0], abs=1e-6)  # Model::SetLinkWorldPose
        assert tip_after[1] == pytest.approx(tip_before[1], abs=1e-6)
        assert math.dist(robot.body.frame_pose().position, base_before) > 0.2  # the model moved around it
    finally:
        w.close()


def test_an_unknown_frame_or_a_short_point_is_refused_and_physics_stays_on(tmp_path):
    w, robot = spawn(tmp_path)
    try:
        play = w.fake.subscribers['/set_joint_trajectory']
        play(trajectory([((0.5, 0.5, 0.0), 1.0)], frame=''))  # upstream: '' is no world frame and no link
        play(trajectory([((0.5,), 1.0)], names=('shoulder', 'elbow')))
        w.run(0.01)
        assert len(w.errors('needs a reference link [] as frame_id, aborting')) == 1
        assert len(w.errors('point 0 has 1 positions for 2 joint_names')) == 1
        assert w.sim.physics_enabled is True and abs(angles(w, robot)[0]) > 1e-5  # swinging, nothing set
    finally:
        w.close()


def test_a_trajectory_during_one_leaves_physics_off_as_upstream(tmp_path):
    w, robot = spawn(tmp_path)
    try:
        play = w.fake.subscribers['/set_joint_trajectory']
        play(trajectory([((0.5, 0.0), 0.01)], names=('shoulder', 'elbow')))
        w.run(0.002)
        play(trajectory([((0.7, 0.0), 0.01)], names=('shoulder', 'elbow')))
        w.run(0.05)
        assert angles(w, robot)[0] == pytest.approx(0.7, abs=1e-9)
        assert len(w.warnings('physics stays off after it ends')) == 1
        assert w.sim.physics_enabled is False  # upstream saved "off" with the second trajectory
        w.manager.on_delete(robot)  # a deleted plugin turns it back on (upstream would not)
        assert w.sim.physics_enabled is True
    finally:
        w.close()


def test_namespace_an_empty_topic_and_unused_parameters(tmp_path):
    w, _ = spawn(tmp_path, '<robotNamespace>arm1</robotNamespace><topicName>play</topicName>'
                           '<serviceName>set_it</serviceName>')
    try:
        assert set(w.fake.subscribers) == {'/arm1/play'}
        assert [m for level, m in w.fake.logs if level == 'info' and '<serviceName> is not used' in m]
    finally:
        w.close()
    w, _ = spawn(tmp_path, '<topicName></topicName>')
    try:
        assert w.fake.subscribers == {} and not w.errors()
    finally:
        w.close()

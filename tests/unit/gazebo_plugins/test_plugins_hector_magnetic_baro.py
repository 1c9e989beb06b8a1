"""hector's magnetometer (libhector_gazebo_ros_magnetic.so) and barometer (libhector_gazebo_ros_baro.so) on a real
Simulator: the earth's field from declination, inclination and magnitude turned into the link's axes at a known
yaw, hector's error model on it; the pressure altitude of a link at a known height and the barometric formula."""
import math

import pytest

from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_baro import pressure
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_magnetic import world_field
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion

from model_plugin_sim import PluginWorld

MAGNETIC = '<plugin name="mag" filename="libhector_gazebo_ros_magnetic.so">%s</plugin>'
BARO = '<plugin name="baro" filename="libhector_gazebo_ros_baro.so">%s</plugin>'


def box(*plugins):
    return """<robot name="box">
 <link name="box"><inertial><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
 <gazebo>%s</gazebo>
</robot>""" % ''.join(plugins)


def spawn(tmp_path, *plugins, yaw=0.0, z=0.1, namespace='/'):
    w = PluginWorld(tmp_path)
    robot = w.spawn('box', box(*plugins), namespace, (0.0, 0.0, z))
    frame = robot.body.com_pose_for_frame((0.0, 0.0, z), rpy_to_quaternion(0.0, 0.0, yaw))
    robot.body.set_pose(frame.position, frame.orientation)
    assert not w.errors() and not w.warnings(), (w.errors(), w.warnings())
    return w, robot


def messages(w, topic):
    return w.fake.publishers[topic].messages


def test_the_field_in_the_body_frame_at_a_known_yaw(tmp_path):
    w, _ = spawn(tmp_path, MAGNETIC % '', yaw=math.pi / 2, namespace='/uav')
    try:
        w.run(0.05)
        msgs = messages(w, '/uav/magnetic')
        assert len(msgs) == 50  # updateRate 0: every world update, listened to or not
        m = msgs[-1]
        assert m.header.frame_id == 'box' and m.header.stamp.to_sec() == pytest.approx(0.05)
        # magnitude 1, inclination 60 deg: (0.5, 0, -0.866) in the world (x north); the body turned 90 deg left
        # sees north on its -y axis (resting on the ground: tilted by ~1e-5)
        assert (m.vector.x, m.vector.y, m.vector.z) == pytest.approx((0.0, -0.5, -math.sqrt(3) / 2), abs=1e-4)
        assert '/uav/magnetic' in w.servers  # SensorModel's dynamic_reconfigure, in the topic's namespace
    finally:
        w.close()


def test_declination_heading_magnitude_offset_and_the_magnetic_field_message(tmp_path):
    params = ('<topicName>compass</topicName><frameId>mag_frame</frameId><magnitude>0.5</magnitude>'
              '<referenceHeading>30</referenceHeading><declination>10</declination><inclination>45</inclination>'
              '<offset>0.1 0 0</offset><updateRate>10</updateRate><useMagneticFieldMsgs>true</useMagneticFieldMsgs>')
    w, _ = spawn(tmp_path, MAGNETIC % params, yaw=math.radians(20))
    try:
        w.run(1.0)
        msgs = messages(w, '/compass')
        assert [round(m.header.stamp.to_sec(), 3) for m in msgs] == pytest.approx([0.1 * k for k in range(1, 11)])
        m = msgs[-1]
        assert type(m).__name__ == 'MagneticField' and m.header.frame_id == 'mag_frame'
        h = 0.5 * math.cos(math.radians(45))
        world = (h * math.cos(math.radians(20)), h * math.sin(math.radians(20)), -0.5 * math.sin(math.radians(45)))
        assert world_field(0.5, math.radians(30), math.radians(10), math.radians(45)) == pytest.approx(world)
        # heading - declination = 20 deg = the body's yaw: the horizontal field lies along the body's x
        f = m.magnetic_field
        assert (f.x, f.y, f.z) == pytest.approx((h + 0.1, 0.0, -0.5 * math.sin(math.radians(45))), abs=1e-4)
    finally:
        w.close()


def test_gaussian_noise_on_each_axis(tmp_path):
    w, _ = spawn(tmp_path, MAGNETIC % '<gaussianNoise>0.02 0.02 0</gaussianNoise>')
    try:
        w.run(2.0)
        xs = [m.vector.x for m in messages(w, '/magnetic')]
        zs = [m.vector.z for m in messages(w, '/magnetic')]
        mean = sum(xs) / len(xs)
        sd = math.sqrt(sum((x - mean) ** 2 for x in xs) / len(xs))
        assert mean == pytest.approx(0.5, abs=0.003) and sd == pytest.approx(0.02, rel=0.15)
        assert max(abs(z + math.sqrt(3) / 2) for z in zs) < 1e-4  # no noise on z
    finally:
        w.close()


def test_pressure_altitude_at_a_known_height(tmp_path):
    params = '<bodyName>box</bodyName><elevation>500</elevation><updateRate>10</updateRate>'
    w, robot = spawn(tmp_path, BARO % params, namespace='/uav')
    try:
        w.run(0.95)
        frame = robot.body.com_pose_for_frame((0.0, 0.0, 1000.0), (0.0, 0.0, 0.0, 1.0))
        robot.body.set_pose(frame.position, frame.orientation)  # at rest 1000 m up, 50 ms to fall
        w.run(0.1)
        height, altimeter = messages(w, '/uav/pressure_height')[-1], messages(w, '/uav/altimeter')[-1]
        assert height.header.stamp.to_sec() == pytest.approx(1.0) and altimeter.header.stamp == height.header.stamp
        assert height.header.frame_id == altimeter.header.frame_id == 'box'
        fallen = 0.5 * 9.8 * 0.05 ** 2
        assert height.point.z == pytest.approx(1000.0 - fallen, abs=0.002)
        assert altimeter.altitude == pytest.approx(height.point.z + 500.0)
        assert altimeter.qnh == 1013.25
        # hector's barometric formula at 1500 m: 1013.25 * (1 - 1500 / 44330)^(1 / 0.19) = 845.35 hPa (its exponent
        # 1/0.19 puts it 0.25 hPa below the standard atmosphere's 845.6)
        assert altimeter.pressure == pytest.approx(845.35, abs=0.02)
        assert altimeter.pressure == pytest.approx(pressure(altimeter.altitude, 1013.25))
        assert len(messages(w, '/uav/altimeter')) == 10 and '/uav/altimeter' in w.servers
        z = link_motion(w.sim.world, robot.body, 'box')[0][2]
        assert z < height.point.z  # still falling: the reading was of the link, not a constant
    finally:
        w.close()


def test_baro_offset_qnh_and_no_height_topic(tmp_path):
    params = '<topicName></topicName><qnh>1000</qnh><offset>2.5</offset><updateRate>10</updateRate>'
    w, robot = spawn(tmp_path, BARO % params)
    try:
        w.run(0.5)
        assert '/pressure_height' not in w.fake.publishers
        m = messages(w, '/altimeter')[-1]
        z = link_motion(w.sim.world, robot.body, 'box')[0][2]
        assert m.altitude == pytest.approx(z + 2.5, abs=1e-3) and m.qnh == 1000.0
        assert m.pressure == pytest.approx(1000.0 * (1 - m.altitude / 44330.0) ** 5.263157)
        assert m.header.stamp.to_sec() == 0.0  # upstream copies the height message's header, never stamped here
    finally:
        w.close()

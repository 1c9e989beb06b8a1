"""hector_gazebo_plugins' GPS (libhector_gazebo_ros_gps.so): the local-to-WGS84 maths and error model of
gazebo_ros_gps.cpp / sensor_model.h (kinematics/navsat.py), and on a real Simulator with the skid-steer
fixture its topics, rate, reference and frames."""
import math
import random

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.kinematics.navsat import ErrorModel, GeoReference
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_gps import update_due
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion

from model_plugin_sim import PluginWorld, fixture_urdf

GPS = ('<gazebo><plugin name="gps_controller" filename="libhector_gazebo_ros_gps.so"><updateRate>%s</updateRate>'
       '<bodyName>base_link</bodyName><frameId>base_link</frameId><topicName>navsat/fix</topicName>'
       '<velocityTopicName>navsat/vel</velocityTopicName><referenceLatitude>49.9</referenceLatitude>'
       '<referenceLongitude>8.9</referenceLongitude><referenceHeading>%s</referenceHeading>'
       '<referenceAltitude>100</referenceAltitude><drift>0.0001 0.0001 0.0001</drift>'
       '<gaussianNoise>0.0001 0.0001 0.0001</gaussianNoise><velocityDrift>0 0 0</velocityDrift>'
       '<velocityGaussianNoise>0 0 0</velocityGaussianNoise></plugin></gazebo></robot>')


def test_local_positions_to_latitude_and_longitude_as_hector():
    ref = GeoReference(49.9, 8.9, 0.0, 100.0)
    assert ref.fix((0.0, 0.0, 0.0)) == (49.9, 8.9, 100.0)
    north, east = ref.radii()
    assert 6.36e6 < north < 6.39e6 and east == pytest.approx(north * math.cos(math.radians(49.9)), rel=0.01)
    lat, lon, alt = ref.fix((1000.0, 0.0, 2.0))  # heading 0: x is north
    assert lat == pytest.approx(49.9 + 1000.0 / north * 180 / math.pi) and lon == 8.9 and alt == 102.0
    lat, lon, _ = ref.fix((0.0, 1000.0, 0.0))    # and y west: the longitude falls
    assert lat == 49.9 and lon == pytest.approx(8.9 - 1000.0 / east * 180 / math.pi)
    turned = GeoReference(49.9, 8.9, math.pi / 2, 0.0)  # heading 90 deg: y is north
    assert turned.fix((0.0, 1000.0, 0.0))[0] == pytest.approx(49.9 + 1000.0 / north * 180 / math.pi)
    assert turned.velocity((1.0, 2.0, 3.0)) == pytest.approx((2.0, -1.0, 3.0))


def test_error_model_scale_offset_drift_and_noise():
    plain = ErrorModel(random.Random(1))
    assert plain.apply((1.0, 2.0, 3.0), 0.25) == (1.0, 2.0, 3.0)
    biased = ErrorModel(random.Random(1), offset=(0.5, 0.0, 0.0), scale_error=(2.0, 1.0, 1.0))
    assert biased.apply((1.0, 2.0, 3.0), 0.25) == (2.5, 2.0, 3.0)
    noisy = ErrorModel(random.Random(2), gaussian_noise=(0.1, 0.1, 0.1))
    xs = [noisy.apply((0.0, 0.0, 0.0), 0.25)[0] for _ in range(4000)]
    assert abs(sum(xs) / len(xs)) < 0.01 and (sum(x * x for x in xs) / len(xs)) ** 0.5 == pytest.approx(0.1, rel=0.05)
    drifting = ErrorModel(random.Random(3), drift=(1.0, 0.0, 0.0), drift_frequency=(0.5, 0.5, 0.5))
    walk = [drifting.apply((0.0, 0.0, 0.0), 0.25)[0] for _ in range(200)]
    assert all(b != a for a, b in zip(walk, walk[1:])) and max(abs(w) for w in walk) < 6.0  # a bounded random walk
    assert ErrorModel(random.Random(1), drift=(0.3, 0, 0), gaussian_noise=(0.4, 0, 0)).variance()[0] == \
        pytest.approx(0.25)


def test_update_timer_fires_on_multiples_of_the_period():
    step = 0.001
    fired = [k for k in range(1, 2001) if update_due(k * step, 0.25, step)]
    assert [k * step for k in fired] == pytest.approx([0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0])
    assert update_due(0.1234, 0.0, step)


def test_fix_and_velocity_topics_on_a_driving_robot(tmp_path):
    urdf = fixture_urdf('skid_steer_bot').replace('</robot>', GPS % (4, 0))
    w = PluginWorld(tmp_path)
    try:
        robot = w.spawn('skid_steer_bot', urdf, '/skid', (0.0, 0.0, 0.1))
        assert not w.errors(), w.errors()
        w.run(1.0)
        fixes = w.fake.publishers['/skid/navsat/fix'].messages
        assert [round(m.header.stamp.to_sec(), 3) for m in fixes] == [0.25, 0.5, 0.75, 1.0]  # 4 Hz, as hector
        first = fixes[-1]
        assert first.header.frame_id == 'base_link' and first.status.status == 0
        assert first.latitude == pytest.approx(49.9, abs=1e-6) and first.longitude == pytest.approx(8.9, abs=1e-6)
        assert first.position_covariance[0] == pytest.approx(2e-8) and first.position_covariance_type == 2
        cmd = Twist()
        cmd.linear.x = 0.5
        w.fake.subscribers['/skid/cmd_vel'](cmd)
        w.run(2.0)
        last = w.fake.publishers['/skid/navsat/fix'].messages[-1]
        x = robot.body.frame_pose().position[0]
        assert x > 0.5 and last.latitude - 49.9 == pytest.approx(x / 6.366e6 * 180 / math.pi, rel=0.05)
        vel = w.fake.publishers['/skid/navsat/vel'].messages[-1]
        assert vel.vector.x == pytest.approx(0.5, abs=0.1)  # heading 0: x is north
    finally:
        w.close()


def test_set_reference_geopose_and_the_reconfigure_servers(tmp_path):
    from geographic_msgs.msg import GeoPoint, GeoPose
    from geometry_msgs.msg import Quaternion
    from hector_gazebo_plugins.srv import SetReferenceGeoPoseRequest
    urdf = fixture_urdf('skid_steer_bot').replace('</robot>', GPS % (4, 0))
    w = PluginWorld(tmp_path)
    try:
        robot = w.spawn('skid_steer_bot', urdf, '/skid', (0.0, 0.0, 0.1))
        w.run(0.3)
        # a new reference: the origin at 10 N 20 E, 100 m up; the pose's yaw pi/6 is hector's heading pi/3
        q = rpy_to_quaternion(0.0, 0.0, math.pi / 6)
        w.fake.services['/skid/navsat/fix/set_reference_geopose'](SetReferenceGeoPoseRequest(
            geo_pose=GeoPose(GeoPoint(10.0, 20.0, 100.0), Quaternion(*q))))
        cmd = Twist()
        cmd.linear.x = 0.5
        w.fake.subscribers['/skid/cmd_vel'](cmd)
        w.run(2.0)
        w.fake.subscribers['/skid/cmd_vel'](Twist())
        w.run(1.0)  # stopped: the last fix is where it stands
        fix = w.fake.publishers['/skid/navsat/fix'].messages[-1]
        x, y, _ = robot.body.frame_pose().position
        e2 = 2 / 298.257223563 - (1 / 298.257223563) ** 2  # WGS84; hector keeps the first reference's radii
        north_radius = 6378137.0 * (1 - e2) / (1 - e2 * math.sin(math.radians(49.9)) ** 2) ** 1.5
        north = math.cos(math.pi / 3) * x + math.sin(math.pi / 3) * y
        assert fix.altitude == pytest.approx(100.0, abs=0.2)
        assert fix.latitude - 10.0 == pytest.approx(north / north_radius * 180 / math.pi, rel=0.002)
        assert fix.longitude > 20.0  # x turned by heading pi/3 has an east part
        # status reconfigure: no fix
        status = w.servers['/skid/navsat/fix/status']
        assert status.config['STATUS_FIX'] and not status.config['SERVICE_GPS']  # hector's defaults: 0, 0
        status.change(STATUS_FIX=False, SERVICE_GALILEO=True)
        w.run(0.25)
        fix = w.fake.publishers['/skid/navsat/fix'].messages[-1]
        assert (fix.status.status, fix.status.service) == (-1, 8)
        w.servers['/skid/navsat/fix/position'].change(offset=2.0)
        w.run(0.25)
        assert w.fake.publishers['/skid/navsat/fix'].messages[-1].altitude == pytest.approx(102.0, abs=0.2)
    finally:
        w.close()


def test_a_body_that_is_no_link_refuses_the_plugin(tmp_path):
    urdf = fixture_urdf('skid_steer_bot').replace('</robot>', (GPS % (4, 0)).replace('>base_link</bodyName>',
                                                                                      '>nope</bodyName>'))
    w = PluginWorld(tmp_path)
    try:
        w.spawn('skid_steer_bot', urdf, '/skid', (0.0, 0.0, 0.1))
        assert w.errors('nope'), w.errors()
        assert '/skid/navsat/fix' not in w.fake.publishers
    finally:
        w.close()

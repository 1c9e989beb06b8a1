"""The racebot's four sensor blocks read as gazebo_ros's plugins read them: kinds, topics, frames
and rates come from the URDF (no master, no physics)."""
import pytest

from racebot_sim_bridge import urdf_model
from racebot_sim_bridge.sensors.config import SensorConfigError, join_topic, plugin_kind, sensor_config


@pytest.fixture(scope='module')
def configs(racebot_xml):
    model = urdf_model.parse_urdf(racebot_xml)
    return {c.kind: c for c in (sensor_config(s, '/', 'racebot') for s in model.sensors)}  # spawn_model at the root


def test_lidar(configs):
    c = configs['laser']
    assert (c.name, c.reference, c.frame_id, c.rate) == ('hokuyo_sensor', 'lidar', 'lidar', 40.0)
    assert c.topics == {'scan': '/scan'}


def test_camera(configs):
    c = configs['camera']
    assert (c.reference, c.frame_id, c.rate) == ('camera', 'camera', 30.0)  # plugin updateRate 0: the sensor's
    assert c.topics == {'image': '/rrbot/camera1/image_raw', 'info': '/rrbot/camera1/camera_info'}
    assert c.params['baseline'] == pytest.approx(0.07)
    assert c.params['distortion'] == [0.0] * 5


def test_depth_camera(configs):
    c = configs['depth']
    assert (c.reference, c.frame_id, c.rate) == ('real_sense', 'realsense_depth', 20.0)
    assert c.topics == {'image': '/real_sense/rgb/image_raw', 'info': '/real_sense/rgb/camera_info',
                        'depth': '/real_sense/depth/image_raw', 'depth_info': '/real_sense/depth/camera_info',
                        'points': '/real_sense/depth/points'}
    assert (c.params['cutoff'], c.params['cutoff_max']) == (0.4, 5.0)
    assert c.params['baseline'] == 0.0  # the URDF's <baseline> is not a gazebo_ros_camera_utils parameter


def test_imu(configs):
    c = configs['imu']
    assert (c.reference, c.frame_id, c.rate) == ('imu', 'imu', 100.0)
    assert c.topics == {'imu': '/imu'}
    assert c.params['gaussian_noise'] == 0.0 and c.params['rpy_offset'] == (0.0, 0.0, 0.0)


def test_names():
    assert plugin_kind('libgazebo_ros_laser.so') == 'laser'
    assert plugin_kind('/opt/lib/libgazebo_ros_openni_kinect.so') == 'depth'
    assert plugin_kind('libgazebo_ros_control.so') is None
    assert join_topic('', 'rrbot/camera1', 'image_raw') == '/rrbot/camera1/image_raw'
    assert join_topic('/robot', 'cam', '/abs/topic') == '/abs/topic'
    assert join_topic('robot/', '', 'scan') == '/robot/scan'


def _sensor(body, plugin):
    xml = ('<robot name="r"><link name="a"/><gazebo reference="a">%s</gazebo></robot>'
           % body.replace('PLUGIN', plugin))
    return urdf_model.parse_urdf(xml).sensors[0]


def test_plugin_rules_and_mismatches():
    ray = ('<sensor type="ray" name="s"><update_rate>10</update_rate><ray><scan><horizontal><samples>5'
           '</samples></horizontal></scan><range><min>0.1</min><max>4</max></range></ray>PLUGIN</sensor>')
    laser = sensor_config(_sensor(ray, '<plugin name="p" filename="libgazebo_ros_laser.so">'
                                       '<robotNamespace>bot</robotNamespace><topicName>laser</topicName>'
                                       '<frameName>/laser_link</frameName></plugin>'))
    assert laser.topics['scan'] == '/bot/laser' and laser.frame_id == 'laser_link'
    assert sensor_config(_sensor(ray, '')) is None  # no ROS plugin: publishes nothing
    with pytest.raises(SensorConfigError):
        sensor_config(_sensor(ray, '<plugin name="p" filename="libgazebo_ros_camera.so"/>'))
    imu = ('<sensor type="imu" name="i"><update_rate>200</update_rate>PLUGIN</sensor>')
    c = sensor_config(_sensor(imu, '<plugin name="p" filename="libgazebo_ros_imu_sensor.so">'
                                   '<updateRateHZ>50</updateRateHZ><topicName>imu</topicName></plugin>'))
    assert c.rate == 50.0  # the plugin throttles
    assert c.frame_id == 'a' and c.warnings  # no frameName: the link, with a warning

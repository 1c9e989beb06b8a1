"""The racebot's four sensor blocks read as gazebo_ros's plugins read them: kinds, topics, frames
and rates come from the URDF (no master, no physics)."""
import pytest

from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.gazebo_plugins.sensor_manager import sensor_config
from racebot_sim_bridge.sensors.config_types import resolve_frame, SensorConfigError, join_topic


@pytest.fixture(scope='module')
def configs(racebot_xml):
    model = urdf_reader.parse_urdf(racebot_xml)
    return {c.kind: c for c in (sensor_config(s, '/', 'racebot') for s in model.sensors)}  # spawn_model at the root


def test_lidar(configs):
    c = configs['laser']
    # every sensor link of the racebot hangs on fixed joints: Gazebo mounts the sensors on base_footprint
    assert (c.name, c.reference, c.frame_id, c.rate) == ('hokuyo_sensor', 'base_footprint', 'lidar', 40.0)
    assert c.topics == {'scan': '/scan'}


def test_camera(configs):
    c = configs['camera']
    assert (c.reference, c.frame_id, c.rate) == ('base_footprint', 'camera', 30.0)  # plugin updateRate 0: the sensor's
    assert c.topics == {'image': '/rrbot/camera1/image_raw', 'info': '/rrbot/camera1/camera_info'}
    assert c.params['baseline'] == pytest.approx(0.07)
    assert c.params['distortion'] == [0.0] * 5


def test_depth_camera(configs):
    c = configs['depth']
    assert (c.reference, c.frame_id, c.rate) == ('base_footprint', 'realsense_depth', 20.0)
    assert c.topics == {'image': '/real_sense/rgb/image_raw', 'info': '/real_sense/rgb/camera_info',
                        'depth': '/real_sense/depth/image_raw', 'depth_info': '/real_sense/depth/camera_info',
                        'points': '/real_sense/depth/points'}
    assert (c.params['cutoff'], c.params['cutoff_max']) == (0.4, 5.0)
    assert c.params['baseline'] == 0.0  # the URDF's <baseline> is not a gazebo_ros_camera_utils parameter


def test_imu(configs):
    c = configs['imu']
    assert (c.reference, c.frame_id, c.rate) == ('base_footprint', 'imu', 100.0)
    assert c.topics == {'imu': '/imu'}
    assert c.params['gaussian_noise'] == 0.0 and c.params['rpy_offset'] == (0.0, 0.0, 0.0)


def test_join_topic():
    assert join_topic('', 'rrbot/camera1', 'image_raw') == '/rrbot/camera1/image_raw'
    assert join_topic('/robot', 'cam', '/abs/topic') == '/abs/topic'
    assert join_topic('robot/', '', 'scan') == '/robot/scan'


def _sensor(body, plugin):
    xml = ('<robot name="r"><link name="a"/><gazebo reference="a">%s</gazebo></robot>'
           % body.replace('PLUGIN', plugin))
    return urdf_reader.parse_urdf(xml).sensors[0]


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
                                   '<updateRateHZ>50</updateRateHZ><topicName>imu</topicName>'
                                   '<frameName>/imu_link</frameName></plugin>'))
    assert c.rate == 50.0  # the plugin throttles
    assert c.frame_id == '/imu_link'  # as written: gazebo_ros_imu_sensor resolves nothing
    # without frameName gazebo_ros_imu_sensor stops ("cannot proceed"): refused, saying what to add
    with pytest.raises(SensorConfigError, match='frameName'):
        sensor_config(_sensor(imu, '<plugin name="p" filename="libgazebo_ros_imu_sensor.so">'
                                   '<topicName>imu</topicName></plugin>'))


def test_laser_and_camera_frames_as_upstream_resolves_them():
    """Row c/d of issue 17's audit: gazebo_ros_laser's frameName defaults to /world (frame_id `world`), a
    camera's has no default; both are resolved with the tf_prefix parameter of the plugin's namespace
    (tf::resolve), which the sensor manager reads from config.params['tf_prefix_param']."""
    ray = ('<sensor type="ray" name="s"><update_rate>10</update_rate><ray><scan><horizontal><samples>5'
           '</samples></horizontal></scan><range><min>0.1</min><max>4</max></range></ray>PLUGIN</sensor>')
    laser = sensor_config(_sensor(ray, '<plugin name="p" filename="libgazebo_ros_laser.so">'
                                       '<robotNamespace>bot</robotNamespace><topicName>scan</topicName></plugin>'))
    assert laser.frame_id == 'world' and laser.params['tf_prefix_param'] == '/bot/tf_prefix'
    resolve_frame(laser, 'bot')
    assert laser.frame_id == 'world'  # a leading slash ignores the prefix
    named = sensor_config(_sensor(ray, '<plugin name="p" filename="libgazebo_ros_laser.so"><topicName>scan'
                                       '</topicName><frameName>hokuyo</frameName></plugin>'))
    resolve_frame(named, 'robot1')
    assert named.frame_id == 'robot1/hokuyo'
    cam = ('<sensor type="camera" name="c"><camera><horizontal_fov>1.0</horizontal_fov><image><width>4</width>'
           '<height>2</height></image><clip><near>0.1</near><far>10</far></clip></camera>PLUGIN</sensor>')
    camera = sensor_config(_sensor(cam, '<plugin name="p" filename="libgazebo_ros_camera.so">'
                                        '<cameraName>cam</cameraName></plugin>'))
    assert camera.frame_id == ''
    resolve_frame(camera, '')
    assert camera.frame_id == ''


def test_camera_update_rate_skips_whole_frames():
    """Row h of issue 17's audit: gazebo_ros_camera's updateRate leaves the sensor's frame rate alone and
    publishes a frame only when a whole plugin period has passed (a 30 Hz sensor at updateRate 20: 15 Hz)."""
    from racebot_sim_bridge.sensors.schedule import FrameThrottle
    cam = ('<sensor type="camera" name="c"><update_rate>30</update_rate><camera><horizontal_fov>1.0</horizontal_fov>'
           '<image><width>4</width><height>2</height></image><clip><near>0.1</near><far>10</far></clip></camera>'
           'PLUGIN</sensor>')
    c = sensor_config(_sensor(cam, '<plugin name="p" filename="libgazebo_ros_camera.so"><cameraName>cam</cameraName>'
                                   '<updateRate>20</updateRate></plugin>'))
    assert c.rate == 30.0 and c.params['update_rate'] == 20.0
    throttle = FrameThrottle(c.params['update_rate'])
    frames = [k / 30.0 for k in range(30)]  # one second of the sensor's frames
    assert sum(throttle.passes(t) for t in frames) == 15


def test_use_depth_16uc1_format_is_openni_kinects():
    depth = ('<sensor type="depth" name="d"><camera><horizontal_fov>1.0</horizontal_fov><image><width>4</width>'
             '<height>2</height></image><clip><near>0.1</near><far>10</far></clip></camera>PLUGIN</sensor>')
    kinect = sensor_config(_sensor(depth, '<plugin name="p" filename="libgazebo_ros_openni_kinect.so">'
                                          '<useDepth16UC1Format>true</useDepth16UC1Format></plugin>'))
    assert kinect.params['depth_16uc1'] is True
    plain = sensor_config(_sensor(depth, '<plugin name="p" filename="libgazebo_ros_openni_kinect.so"/>'))
    assert plain.params['depth_16uc1'] is False
    other = sensor_config(_sensor(depth, '<plugin name="p" filename="libgazebo_ros_depth_camera.so">'
                                         '<useDepth16UC1Format>true</useDepth16UC1Format></plugin>'))
    assert other.params['depth_16uc1'] is False  # only the openni_kinect plugin reads it


def test_auto_distortion_copies_the_sensors_lens_into_d():
    """Row f of issue 17's audit: D = (k1, k2, t1, t2, k3) from the plugin, or with autoDistortion from the
    camera's own <distortion> (k1 k2 k3 p1 p2)."""
    cam = ('<sensor type="camera" name="c"><camera><horizontal_fov>1.0</horizontal_fov><image><width>4</width>'
           '<height>2</height></image><clip><near>0.1</near><far>10</far></clip><distortion><k1>-0.25</k1>'
           '<k2>0.12</k2><k3>0.01</k3><p1>-0.002</p1><p2>0.003</p2><center>0.5 0.5</center></distortion></camera>'
           'PLUGIN</sensor>')
    auto = sensor_config(_sensor(cam, '<plugin name="p" filename="libgazebo_ros_camera.so">'
                                      '<autoDistortion>true</autoDistortion></plugin>'))
    assert auto.params['distortion'] == [-0.25, 0.12, -0.002, 0.003, 0.01]
    given = sensor_config(_sensor(cam, '<plugin name="p" filename="libgazebo_ros_camera.so"><distortionK1>0.1'
                                       '</distortionK1><distortionT2>0.2</distortionT2></plugin>'))
    assert given.params['distortion'] == [0.1, 0.0, 0.0, 0.2, 0.0]
    assert any('not rendered' in w for w in given.warnings)

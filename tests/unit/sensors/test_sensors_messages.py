"""The sensor messages' layout (no master): what a subscriber decodes is what was measured."""
import math
import struct

import numpy as np
import pytest
import rospy

from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.camera import PinholeCamera
from racebot_sim_bridge.sensors.ray import ScanGeometry
from racebot_sim_bridge.description.urdf_model import RaySpec

STAMP = rospy.Time(12, 500000000)


def roundtrip(msg):
    """The message as a subscriber gets it: serialised and read back."""
    from io import BytesIO
    buf = BytesIO()
    msg.serialize(buf)
    out = type(msg)()
    out.deserialize(buf.getvalue())
    return out


def test_laser_scan_fields_and_infinities():
    g = ScanGeometry(RaySpec(samples=5, min_angle=-1, max_angle=1, range_min=0.1, range_max=4))
    scan = roundtrip(msgs.laser_scan(STAMP, 'lidar', g, [1.0, math.inf, -math.inf, 2.5, 0.2]))
    assert scan.header.frame_id == 'lidar' and scan.header.stamp == STAMP
    assert (scan.angle_min, scan.angle_max) == pytest.approx((-1, 1))
    assert scan.angle_increment == pytest.approx(0.5)
    assert (scan.time_increment, scan.scan_time) == (0.0, 0.0)
    assert scan.ranges[1] == math.inf and scan.ranges[2] == -math.inf
    assert scan.ranges[3] == pytest.approx(2.5) and len(scan.intensities) == 5


def test_laser_scan_bytes_are_those_of_the_plain_message():
    # numpy arrays serialized by their bytes (numpy_msg): what a subscriber reads is what a list-filled LaserScan gives
    from io import BytesIO
    from sensor_msgs.msg import LaserScan
    g = ScanGeometry(RaySpec(samples=5, min_angle=-1, max_angle=1, range_min=0.1, range_max=4))
    ranges, retro = [1.0, math.inf, -math.inf, 2.5, 0.2], [0.0, 1.0, 0.0, 0.0, 0.5]
    for intensities in (None, retro):
        ours = msgs.laser_scan(STAMP, 'lidar', g, np.array(ranges), intensities)
        assert isinstance(ours, LaserScan)  # a rospy publisher of LaserScan takes it
        plain = LaserScan(header=ours.header, angle_min=g.angle_min, angle_max=g.angle_max,
                          angle_increment=g.angle_increment, range_min=g.range_min, range_max=g.range_max,
                          ranges=np.asarray(ranges, np.float32).tolist(), intensities=intensities or [0.0] * 5)
        a, b = BytesIO(), BytesIO()
        ours.serialize(a)
        plain.serialize(b)
        assert a.getvalue() == b.getvalue()


def test_images_decode_to_what_was_rendered():
    rgb = np.arange(4 * 6 * 3, dtype=np.uint8).reshape(4, 6, 3)
    img = roundtrip(msgs.rgb_image(STAMP, 'camera', rgb))
    assert (img.width, img.height, img.encoding, img.step, img.is_bigendian) == (6, 4, 'rgb8', 18, 0)
    assert np.array_equal(np.frombuffer(img.data, np.uint8).reshape(4, 6, 3), rgb)
    depth = np.array([[0.5, np.nan], [1.25, 4.0]], dtype=np.float32)
    d = roundtrip(msgs.depth_image(STAMP, 'realsense_depth', depth))
    assert (d.encoding, d.step) == ('32FC1', 8)
    assert np.array_equal(np.frombuffer(d.data, '<f4').reshape(2, 2), depth, equal_nan=True)


def test_camera_info_is_the_pinhole():
    cam = PinholeCamera(640, 480, math.radians(60), 0.05, 8)
    info = roundtrip(msgs.camera_info(STAMP, 'realsense_depth', cam, 0.1, [0.1, 0, 0, 0, 0]))
    assert (info.width, info.height, info.distortion_model) == (640, 480, 'plumb_bob')
    assert list(info.K) == pytest.approx(cam.K()) and list(info.P) == pytest.approx(cam.P(0.1))
    assert list(info.R) == [1, 0, 0, 0, 1, 0, 0, 0, 1] and list(info.D) == pytest.approx([0.1, 0, 0, 0, 0])


def test_point_cloud_layout_and_colour_packing():
    pts = np.array([[[0.1, -0.2, 1.5], [np.nan, np.nan, np.nan]]], dtype=np.float32)
    rgb = np.array([[[200, 100, 50], [1, 2, 3]]], dtype=np.uint8)
    cloud = roundtrip(msgs.point_cloud(STAMP, 'realsense_depth', pts, rgb))
    assert (cloud.width, cloud.height, cloud.point_step, cloud.row_step) == (2, 1, 32, 64)
    assert [(f.name, f.offset) for f in cloud.fields] == [('x', 0), ('y', 4), ('z', 8), ('rgb', 16)]
    assert cloud.is_dense is False
    x, y, z = struct.unpack_from('<fff', cloud.data, 0)
    assert (x, y, z) == pytest.approx((0.1, -0.2, 1.5))
    packed = struct.unpack_from('<I', cloud.data, 16)[0]  # PCL: 0x00RRGGBB
    assert ((packed >> 16) & 255, (packed >> 8) & 255, packed & 255) == (200, 100, 50)
    assert math.isnan(struct.unpack_from('<f', cloud.data, 32)[0])


def test_imu_message():
    m = roundtrip(msgs.imu(STAMP, 'imu', (0, 0, 0, 1), (0.1, 0.2, 0.3), (0, 0, 9.8), noise_stddev=0.1))
    assert m.header.frame_id == 'imu' and m.orientation.w == 1.0
    assert (m.angular_velocity.z, m.linear_acceleration.z) == pytest.approx((0.3, 9.8))
    assert m.angular_velocity_covariance[0] == pytest.approx(0.01) and m.angular_velocity_covariance[1] == 0.0


def test_depth_in_millimetres_as_openni_kinect_writes_16uc1():
    """Row g of issue 17's audit: useDepth16UC1Format gives 16UC1, depth * 1000 truncated, 0 for no reading."""
    depth = np.array([[1.2345, np.nan], [0.5, 70.0]], dtype=np.float32)
    img = roundtrip(msgs.depth_image(STAMP, 'd', depth, millimetres=True))
    assert (img.encoding, img.step) == ('16UC1', 4)
    values = np.frombuffer(img.data, dtype='<u2').reshape(2, 2)
    assert values.tolist() == [[1234, 0], [500, 65535]]
    assert roundtrip(msgs.depth_image(STAMP, 'd', depth)).encoding == '32FC1'


def test_image_encodings_as_gazebo_ros_camera_maps_the_sensor_format():
    """Row j of issue 17's audit: <image><format> -> encoding (gazebo_ros_camera_utils), the pixels converted."""
    rgb = np.array([[[200, 100, 50], [10, 20, 30]], [[0, 255, 0], [1, 2, 3]]], dtype=np.uint8)
    assert msgs.image_encoding('R8G8B8') == 'rgb8' and msgs.image_encoding('L_INT8') == 'mono8'
    assert msgs.image_encoding('NO_SUCH') == 'bgr8'  # upstream's fallback after its error
    bgr = roundtrip(msgs.rgb_image(STAMP, 'c', rgb, 'bgr8'))
    assert (bgr.encoding, bgr.step) == ('bgr8', 6) and bgr.data[:3] == bytes([50, 100, 200])
    mono = roundtrip(msgs.rgb_image(STAMP, 'c', rgb, 'mono8'))
    assert (mono.encoding, mono.step) == ('mono8', 2)
    assert mono.data[0] == round(0.299 * 200 + 0.587 * 100 + 0.114 * 50) and mono.data[2] == round(0.587 * 255)
    mono16 = roundtrip(msgs.rgb_image(STAMP, 'c', rgb, 'mono16'))
    assert mono16.step == 4 and np.frombuffer(mono16.data, '<u2')[2] == round(0.587 * 255) * 257
    rgb16 = roundtrip(msgs.rgb_image(STAMP, 'c', rgb, 'rgb16'))
    assert rgb16.step == 12 and np.frombuffer(rgb16.data, '<u2')[:3].tolist() == [200 * 257, 100 * 257, 50 * 257]
    bayer = roundtrip(msgs.rgb_image(STAMP, 'c', rgb, 'bayer_rggb8'))
    # R at (0, 0), G at (0, 1) and (1, 0), B at (1, 1)
    assert (bayer.encoding, bayer.step, list(bayer.data)) == ('bayer_rggb8', 2, [200, 20, 255, 3])
    assert list(roundtrip(msgs.rgb_image(STAMP, 'c', rgb, 'bayer_bggr8')).data) == [50, 20, 255, 1]


@pytest.mark.parametrize('make', [
    lambda rng, stamp: msgs.rgb_image(stamp, 'cam', rng.integers(0, 256, (6, 5, 3), dtype=np.uint8)),
    lambda rng, stamp: msgs.rgb_image(stamp, 'cam', rng.integers(0, 256, (6, 5, 3), dtype=np.uint8), 'mono16'),
    lambda rng, stamp: msgs.depth_image(stamp, 'cam', rng.uniform(0.1, 5.0, (6, 5)).astype(np.float32)),
    lambda rng, stamp: msgs.depth_image(stamp, 'cam', rng.uniform(0.1, 5.0, (6, 5)).astype(np.float32), True),
    lambda rng, stamp: msgs.point_cloud(stamp, 'cam', rng.uniform(-1, 1, (6, 5, 3)).astype(np.float32),
                                        rng.integers(0, 256, (6, 5, 3), dtype=np.uint8)),
])
def test_large_data_messages_serialize_to_genpys_bytes(make):
    """FastImage / FastPointCloud2 write `data` without genpy's struct.pack copy: the same bytes, the same
    message when read back, header sequence number (set by rospy before serializing) included."""
    import io

    import rospy
    from rospy.msg import serialize_message
    msg = make(np.random.default_rng(7), rospy.Time(12, 345))
    plain = type(msg).__mro__[2]()  # Image or PointCloud2, as genpy generated it
    for slot in plain.__slots__:
        setattr(plain, slot, getattr(msg, slot))
    fast_buff, plain_buff = io.BytesIO(), io.BytesIO()
    serialize_message(fast_buff, 42, msg)
    serialize_message(plain_buff, 42, plain)
    assert fast_buff.getvalue() == plain_buff.getvalue()
    back = type(plain)()
    back.deserialize(fast_buff.getvalue()[4:])
    assert back.header.seq == 42 and back.data == msg.data and back.height == 6 and back.width == 5

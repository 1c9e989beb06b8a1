"""ROS messages of the simulated sensors, filled as gazebo_ros's plugins fill them.

Message classes only (no rospy node, no master): every builder takes the stamp (a rospy.Time or
genpy.Time), the frame id and numpy data.
- LaserScan (gazebo_ros_laser): time_increment = 0 ("instantaneous simulator scan") and
  scan_time = 0, as the plugin sets them; intensities all 0 (no retro-reflectors here).
- Image: rgb8 (3 bytes a pixel) and 32FC1 (little-endian float32 metres).
- CameraInfo (gazebo_ros_camera_utils): plumb_bob with the plugin's distortion coefficients,
  K and P of the pinhole (P[3] = -f * hackBaseline), R identity.
- PointCloud2 (gazebo_ros_openni_kinect): fields x, y, z (float32 at 0, 4, 8) and rgb (float32
  at 16, packed as PCL does: bytes b, g, r, 0), point_step 32, one row per image row,
  is_dense False when any point is NaN. (The Gazebo plugin writes r and b the other way round,
  which shows swapped colours in RViz; this follows PCL.)
- Imu (gazebo_ros_imu_sensor): covariances diagonal with the plugin's gaussianNoise squared.
- Range (gazebo_ros_range): radiation type, field_of_view (the plugin's fov), min/max range of
  the ray sensor, the reading (range_reading.py).
- ContactsState (gazebo_ros_bumper): one ContactState per pair of collisions (contact.py), info
  a debug line naming both and the time, as the plugin writes one.
"""
import copy
import io
import struct

import numpy as np
from gazebo_msgs.msg import ContactState, ContactsState
from geometry_msgs.msg import Vector3, Wrench
from sensor_msgs.msg import CameraInfo, Image, Imu, LaserScan, PointCloud2, PointField, Range
from rospy.numpy_msg import numpy_msg
from std_msgs.msg import Header

NumpyLaserScan = numpy_msg(LaserScan)


class _LargeData:
    """genpy's serialize(), with the uint8[] `data` written as it is. genpy writes it through struct.pack, which
    copies it into a new bytes first: for a 12 MB depth frame a second copy, made holding the interpreter lock
    that the physics thread then waits for (py-spy: the depth camera's serialize was 12 % of the world server's
    samples). The same bytes go out (tests/unit/sensors/test_sensors_messages.py compares them)."""
    _after_data = 0  # bytes genpy writes after `data`

    def serialize(self, buff):
        data = self.data
        if isinstance(data, (list, tuple)):
            return super().serialize(buff)
        rest = copy.copy(self)  # every field but the data, serialized by genpy
        rest.data = b''
        small = io.BytesIO()
        super(_LargeData, rest).serialize(small)
        out = small.getvalue()
        cut = len(out) - 4 - self._after_data  # `data` is its 4-byte length, then its bytes
        buff.write(out[:cut])
        buff.write(struct.pack('<I', len(data)))
        buff.write(data)
        buff.write(out[cut + 4:])


class FastImage(_LargeData, Image):
    """sensor_msgs/Image (data is its last field)."""


class FastPointCloud2(_LargeData, PointCloud2):
    """sensor_msgs/PointCloud2 (data is followed by is_dense, one byte)."""
    _after_data = 1


def header(stamp, frame_id):
    return Header(stamp=stamp, frame_id=frame_id)


def laser_scan(stamp, frame_id, geometry, ranges, intensities=None):
    """`geometry`: ray.ScanGeometry; `ranges`: the reported ranges (inf allowed); `intensities`: the
    laser_retro of what each ray hit (None: all 0). A LaserScan whose arrays are float32 numpy arrays,
    serialized with their bytes (rospy.numpy_msg: the same bytes as the list's, without a Python float per
    beam); its class is a LaserScan, with LaserScan's type and md5sum. (genpy's numpy serializer calls
    ndarray.tostring, deprecated: numpy is pinned in tools/requirements.txt, and a unit test compares the bytes.)"""
    ranges = np.asarray(ranges, dtype=np.float32)
    intensities = (np.zeros(len(ranges), dtype=np.float32) if intensities is None
                   else np.asarray(intensities, dtype=np.float32))
    return NumpyLaserScan(header=header(stamp, frame_id), angle_min=geometry.angle_min, angle_max=geometry.angle_max,
                          angle_increment=geometry.angle_increment, time_increment=0.0, scan_time=0.0,
                          range_min=geometry.range_min, range_max=geometry.range_max,
                          ranges=ranges, intensities=intensities)


# gazebo_ros_camera_utils: the sensor's <image><format> -> the image's encoding (an unknown format is
# published as bgr8, as upstream does after its error)
IMAGE_ENCODINGS = {
    'L8': 'mono8', 'L_INT8': 'mono8', 'L16': 'mono16', 'L_INT16': 'mono16',
    'R8G8B8': 'rgb8', 'RGB_INT8': 'rgb8', 'B8G8R8': 'bgr8', 'BGR_INT8': 'bgr8',
    'R16G16B16': 'rgb16', 'RGB_INT16': 'rgb16',
    'BAYER_RGGB8': 'bayer_rggb8', 'BAYER_BGGR8': 'bayer_bggr8', 'BAYER_GBRG8': 'bayer_gbrg8',
    'BAYER_GRBG8': 'bayer_grbg8',
}
# which colour each cell of a 2 x 2 Bayer tile samples: (row 0 col 0, row 0 col 1, row 1 col 0, row 1 col 1)
BAYER_TILES = {'bayer_rggb8': 'RGGB', 'bayer_bggr8': 'BGGR', 'bayer_gbrg8': 'GBRG', 'bayer_grbg8': 'GRBG'}


def image_encoding(image_format):
    return IMAGE_ENCODINGS.get(image_format, 'bgr8')


def rgb_image(stamp, frame_id, rgb, encoding='rgb8'):
    """An image of a rendered RGB frame (height x width x 3 uint8) in `encoding` (image_encoding()): image_data's."""
    encoding, data = image_data(rgb, encoding)
    height, width = data.shape[:2]
    return FastImage(header=header(stamp, frame_id), height=height, width=width, encoding=encoding, is_bigendian=0,
                     step=data.nbytes // height, data=data.tobytes())


def image_data(rgb, encoding='rgb8'):
    """(encoding, pixels) of a rendered RGB frame (height x width x 3 uint8) in `encoding` (image_encoding()), C
    order, little-endian: mono by ITU-R 601 luminance, 16-bit channels as value * 257 (full scale to full scale),
    Bayer as the mosaic; an encoding not listed is rgb8."""
    rgb = np.ascontiguousarray(rgb, dtype=np.uint8)
    height, width = rgb.shape[:2]
    if encoding == 'bgr8':
        data = rgb[:, :, ::-1]
    elif encoding in ('mono8', 'mono16'):
        luma = np.rint(rgb.astype(np.float32) @ np.array([0.299, 0.587, 0.114], dtype=np.float32)).clip(0, 255)
        data = luma.astype(np.uint8) if encoding == 'mono8' else (luma.astype('<u2') * 257)
    elif encoding == 'rgb16':
        data = rgb.astype('<u2') * 257
    elif encoding in BAYER_TILES:
        tile = BAYER_TILES[encoding]
        data = np.empty((height, width), dtype=np.uint8)
        for k, colour in enumerate(tile):
            data[k // 2::2, k % 2::2] = rgb[k // 2::2, k % 2::2, 'RGB'.index(colour)]
    else:
        encoding, data = 'rgb8', rgb
    return encoding, np.ascontiguousarray(data)


def depth_image(stamp, frame_id, depth, millimetres=False):
    """32FC1 in metres (NaN: no reading), or with `millimetres` (gazebo_ros_openni_kinect's
    useDepth16UC1Format) 16UC1 in whole millimetres, truncated as upstream's float-to-integer assignment,
    0 for no reading (REP 118)."""
    if millimetres:
        mm = np.nan_to_num(np.asarray(depth, dtype=np.float64) * 1000.0, nan=0.0, posinf=0.0, neginf=0.0)
        data = np.ascontiguousarray(np.clip(np.trunc(mm), 0, 65535), dtype='<u2')
        height, width = data.shape
        return FastImage(header=header(stamp, frame_id), height=height, width=width, encoding='16UC1',
                         is_bigendian=0, step=2 * width, data=data.tobytes())
    depth = np.ascontiguousarray(depth, dtype='<f4')
    height, width = depth.shape
    return FastImage(header=header(stamp, frame_id), height=height, width=width, encoding='32FC1', is_bigendian=0,
                     step=4 * width, data=depth.tobytes())


def camera_info(stamp, frame_id, camera, baseline=0.0, distortion=(0.0, 0.0, 0.0, 0.0, 0.0), intrinsics=None):
    """`camera`: camera.PinholeCamera; `intrinsics`: (f, cx, cy) to report (camera.reported_intrinsics())."""
    intrinsics = intrinsics or camera.reported_intrinsics()
    return CameraInfo(header=header(stamp, frame_id), height=camera.height, width=camera.width,
                      distortion_model='plumb_bob', D=list(distortion), K=camera.K(intrinsics),
                      R=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], P=camera.P(baseline, intrinsics))


POINT_FIELDS = [PointField(name='x', offset=0, datatype=PointField.FLOAT32, count=1),
                PointField(name='y', offset=4, datatype=PointField.FLOAT32, count=1),
                PointField(name='z', offset=8, datatype=PointField.FLOAT32, count=1),
                PointField(name='rgb', offset=16, datatype=PointField.FLOAT32, count=1)]
POINT_STEP = 32


def point_cloud(stamp, frame_id, points, rgb):
    """`points`: height x width x 3 float32 (NaN for no point); `rgb`: height x width x 3 uint8."""
    height, width = points.shape[:2]
    buf = np.zeros((height, width, POINT_STEP), dtype=np.uint8)
    buf[:, :, 0:12] = np.ascontiguousarray(points, dtype='<f4').view(np.uint8).reshape(height, width, 12)
    buf[:, :, 16] = rgb[:, :, 2]
    buf[:, :, 17] = rgb[:, :, 1]
    buf[:, :, 18] = rgb[:, :, 0]
    dense = not bool(np.isnan(points).any())
    return FastPointCloud2(header=header(stamp, frame_id), height=height, width=width, fields=POINT_FIELDS,
                           is_bigendian=False, point_step=POINT_STEP, row_step=POINT_STEP * width,
                           data=buf.tobytes(), is_dense=dense)


def imu(stamp, frame_id, orientation, angular_velocity, linear_acceleration, noise_stddev=0.0):
    msg = Imu(header=header(stamp, frame_id))
    msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w = (float(c) for c in orientation)
    msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = (float(c) for c in angular_velocity)
    msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = \
        (float(c) for c in linear_acceleration)
    variance = noise_stddev * noise_stddev
    diagonal = [variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance]
    msg.orientation_covariance = list(diagonal)
    msg.angular_velocity_covariance = list(diagonal)
    msg.linear_acceleration_covariance = list(diagonal)
    return msg


def range_message(stamp, frame_id, radiation, field_of_view, min_range, max_range, reading):
    return Range(header=header(stamp, frame_id), radiation_type=radiation, field_of_view=field_of_view,
                 min_range=min_range, max_range=max_range, range=reading)


def _wrench(force, torque):
    return Wrench(force=Vector3(*force), torque=Vector3(*torque))


def contacts_state(stamp, frame_id, groups, time):
    """`groups`: [contact.ContactGroup]; `time`: the contacts' sim time in seconds (for info)."""
    states = []
    for i, g in enumerate(groups):
        info = 'Debug:  i:(%d/%d)     my geom:%s   other geom:%s         time:%.9f\n' % (
            i, len(groups), g.collision1, g.collision2, time)
        states.append(ContactState(
            info=info, collision1_name=g.collision1, collision2_name=g.collision2,
            wrenches=[_wrench(f, t) for f, t in zip(g.forces, g.torques)],
            total_wrench=_wrench(g.total_force, g.total_torque),
            contact_positions=[Vector3(*p) for p in g.positions],
            contact_normals=[Vector3(*n) for n in g.normals], depths=list(g.depths)))
    return ContactsState(header=header(stamp, frame_id), states=states)

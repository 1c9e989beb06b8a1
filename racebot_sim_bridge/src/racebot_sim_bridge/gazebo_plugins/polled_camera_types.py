"""polled_camera/GetPolledImage (image_common 1.12, noetic), the service gazebo_ros_prosilica answers in polled mode.

Debian packages it as python3-polled-camera; where that is not installed, the same type is generated here with
genpy from upstream's text (the .srv below, sensor_msgs/RegionOfInterest from the installed sensor_msgs), so its
md5 sums are upstream's and a client built against the real package talks to it (tests check the sums). A
catkin stand-in would need sensor_msgs' .msg files, which Debian's python3-sensor-msgs does not ship.
"""
import hashlib

# polled_camera/srv/GetPolledImage.srv as upstream writes it (comments are not part of the md5)
REQUEST = """# Namespace to publish response topics in. A polled camera driver node
# should publish:
#   <response_namespace>/image_raw
#   <response_namespace>/camera_info
string response_namespace

# Timeout for attempting to capture data from the device. This does not
# include latency from ROS communication, post-processing of raw camera
# data, etc. A zero duration indicates no time limit.
duration timeout

# Binning settings, if supported by the camera.
uint32 binning_x
uint32 binning_y

# Region of interest, if supported by the camera.
sensor_msgs/RegionOfInterest roi
"""
RESPONSE = """bool success          # Could the image be captured?
string status_message # Error message in case of failure
time stamp            # Timestamp of the captured image. Can be matched against
                      # incoming sensor_msgs/Image header.
"""
_classes = {}


def get_polled_image():
    """The GetPolledImage service class: Debian's when installed, else one generated with genpy."""
    if 'srv' not in _classes:
        try:
            from polled_camera.srv import GetPolledImage
        except ImportError:
            GetPolledImage = _generated()
        _classes['srv'] = GetPolledImage
    return _classes['srv']


def _generated():
    from genpy.dynamic import generate_dynamic
    from sensor_msgs.msg import RegionOfInterest
    roi = '\n' + '=' * 80 + '\nMSG: sensor_msgs/RegionOfInterest\n' + RegionOfInterest._full_text
    request = generate_dynamic('polled_camera/GetPolledImageRequest', REQUEST + roi)
    response = generate_dynamic('polled_camera/GetPolledImageResponse', RESPONSE)
    request_class = request['polled_camera/GetPolledImageRequest']
    response_class = response['polled_camera/GetPolledImageResponse']
    # genmsg's md5 of a service: of the request's md5 text followed by the response's
    md5 = hashlib.md5((_md5_text(REQUEST, request_class) + _md5_text(RESPONSE, response_class)).encode()).hexdigest()
    return type('GetPolledImage', (), {'_type': 'polled_camera/GetPolledImage', '_md5sum': md5,
                                       '_request_class': request_class, '_response_class': response_class})


def _md5_text(text, msg_class):
    """genmsg's compute_md5_text: constants, then each field as `type name`, a message field as `md5 name`."""
    from genmsg import MsgContext
    from genmsg.gentools import compute_md5_text
    from genmsg.msg_loader import load_msg_from_string
    from sensor_msgs.msg import RegionOfInterest
    context = MsgContext.create_default()
    roi = load_msg_from_string(context, RegionOfInterest._full_text, 'sensor_msgs/RegionOfInterest')
    context.register('sensor_msgs/RegionOfInterest', roi)
    spec = load_msg_from_string(context, text, msg_class._type)
    return compute_md5_text(context, spec)

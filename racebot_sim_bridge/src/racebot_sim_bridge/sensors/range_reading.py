"""What gazebo_ros_range makes of a ray sensor's rays: one sensor_msgs/Range reading.

Pure numpy: no rospy, no pybullet. gazebo_ros_range (noetic-devel) reads the ray shape itself, not
the LaserScan ranges: a ray that hits nothing has the shape's full length, range max (never +inf),
and a hit reads range min + the distance along the ray from range min. The reading is the smallest
of all rays (all layers); when it is below range max it gets N(0, gaussianNoise) and is clamped
from above only, to range max (so noise may take it below range min, as upstream lets it).
radiation: the text 'ultrasound' is ULTRASOUND (0); anything else is INFRARED (1).
"""
import numpy as np

ULTRASOUND = 0  # sensor_msgs/Range.ULTRASOUND
INFRARED = 1    # sensor_msgs/Range.INFRARED


def radiation_type(text):
    """The Range radiation_type gazebo_ros_range sets for a <radiation> text."""
    return ULTRASOUND if text == 'ultrasound' else INFRARED


def ray_lengths(fractions, hit, range_min, range_max):
    """The ray shape's range per ray: range_min + the hit's distance along [range_min, range_max],
    range_max where the ray hits nothing."""
    fractions = np.asarray(fractions, dtype=np.float64)
    lengths = range_min + fractions * (range_max - range_min)
    return np.where(np.asarray(hit, dtype=bool), lengths, float(range_max))


def range_reading(lengths, range_max, noise_sample=0.0):
    """The Range.range of the rays' `lengths`: their minimum, plus `noise_sample` (a draw of
    N(0, gaussianNoise)) and clamped to range_max when it is below range_max (as float32, the
    message's type, compares it)."""
    lengths = np.asarray(lengths, dtype=np.float32)
    reading = np.float32(lengths.min()) if lengths.size else np.float32(np.finfo(np.float32).max)
    if reading < np.float32(range_max):
        reading = np.float32(min(float(reading) + noise_sample, range_max))
    return float(reading)

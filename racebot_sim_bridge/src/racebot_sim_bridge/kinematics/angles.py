"""ROS's angles package, the part ros_control and ros_controllers use: the shortest angle between two, and the
one that stays within a joint's limits. Plain maths (radians).

hardware_interface.py unwraps every revolute joint's position with shortest_angular_distance, every world
update: CMakeLists.txt compiles this module with Cython (typed by angles.pxd) so that its compiled callers call
these as C functions; without the build it runs as plain Python with the same results."""
import math

_PI = math.pi


def shortest_angular_distance(a, b):
    """Signed smallest angle that takes a to b, in (-pi, pi]."""
    d = math.fmod(b - a, 2.0 * math.pi)
    if d > math.pi:
        d -= 2.0 * math.pi
    elif d <= -math.pi:
        d += 2.0 * math.pi
    return d


def shortest_angular_distance_with_limits(current, target, lower, upper):
    """Error that takes `current` to `target` without leaving [lower, upper] (angles' idea of
    shortest_angular_distance_with_large_limits): the short way round if it stays inside the
    limits, else the long way."""
    delta = shortest_angular_distance(current, target)
    if lower - 1e-12 <= current + delta <= upper + 1e-12:
        return delta
    other = delta - math.copysign(2.0 * _PI, delta) if delta != 0.0 else 0.0
    if lower - 1e-12 <= current + other <= upper + 1e-12:
        return other
    return delta

"""The kinematics of drives and controllers as plain functions: no rospy, no PyBullet, unit-tested
(tests/unit/kinematics/). The plugins and controllers wrap them with their ROS plumbing.

differential.py runs every world update for every diff-drive robot, angles.py for every revolute joint (through
ros_control's hardware_interface): CMakeLists.txt compiles them with Cython into the devel (or install) space's copy
of this folder, which therefore comes first on this package's path; without the build they run as plain Python
with the same results."""
from pkgutil import extend_path

__path__ = [p for p in extend_path([], __name__) if p not in __path__] + list(__path__)

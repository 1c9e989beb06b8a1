"""A URDF robot (the expanded robot_description) as plain dataclasses, and the queries on it.

Pure Python: no rospy, no pybullet. urdf_reader.parse_urdf builds a RobotModel from URDF text, checking what
urdfdom checks, and reads the Gazebo extensions gazebo_ros uses (``<gazebo reference=...>`` properties and
sensors, ``<gazebo><plugin>`` blocks, ``<transmission>`` elements as ros_control's transmission parser reads
them). The RobotModel answers where Gazebo lumps a link on fixed joints; sdf_reduction rewrites its extensions as
sdformat does when it lumps one (parse_urdf applies it). gazebo_ros_control/robot_hw_sim.py
applies DefaultRobotHWSim's rules to the transmissions (one joint and one hardware interface each).

Anything wrong raises ``UrdfError`` saying what is wrong and what to do. Things the simulator can live with
are listed in ``RobotModel.warnings`` instead.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TypeVar

from racebot_sim_bridge.description import xml_values
from racebot_sim_bridge.description.geometry import Shape
from racebot_sim_bridge.description.plugin_library import library_key
from racebot_sim_bridge.kinematics.rotations import Transform, compose

__all__ = [
    'UrdfError', 'RobotModel', 'UrdfLink', 'Inertial', 'Geometry', 'UrdfJoint', 'Limit', 'Dynamics', 'Mimic',
    'Transmission', 'GazeboPlugin', 'GazeboElement', 'Rewrite', 'SensorSpec', 'RaySpec', 'CameraSpec', 'ImuSpec',
    'normalise_interface', 'JOINT_TYPES', 'KEEP_FIXED_JOINT',
]

JOINT_TYPES = ('revolute', 'continuous', 'prismatic', 'fixed', 'floating', 'planar')
# The two <gazebo reference> switches that keep a fixed joint and its child link (sdformat: on the JOINT's
# reference; urdf_reader keeps them as booleans).
KEEP_FIXED_JOINT = ('preserveFixedJoint', 'disableFixedJointLumping')

_Value = TypeVar('_Value')  # what one of xml_values' readers gives


class UrdfError(ValueError):
    """The robot description cannot be used; the message says why and what to change."""

    # How a URDF words an xml_values.BadValue about `what`.
    _WORDING = {
        xml_values.Problem.NUMBER: '%(what)s: %(text)r is not a number; give a plain decimal number',
        xml_values.Problem.FINITE: '%(what)s: %(text)r is not finite; give a finite number',
        xml_values.Problem.COUNT: '%(what)s: expected %(count)d numbers separated by spaces, got %(text)r',
        xml_values.Problem.INTEGER: '%(what)s: %(text)r is not a whole number',
        xml_values.Problem.BOOLEAN: '%(what)s: %(text)r is not true or false',
    }

    @classmethod
    def of(cls, bad: xml_values.BadValue, what: str) -> UrdfError:
        """The UrdfError of an xml_values.BadValue found in `what`."""
        return cls(cls._WORDING[bad.problem] % {'what': what, 'text': bad.text, 'count': bad.count})


def read_value(read: Callable[..., _Value], text: str | None, what: str, *args: int) -> _Value:
    """read(text, *args), one of xml_values' readers; its BadValue raised as the UrdfError about `what`."""
    try:
        return read(text, *args)
    except xml_values.BadValue as bad:
        raise UrdfError.of(bad, what) from None


def number(text: str | None, what: str) -> float:
    """A finite number from URDF text; UrdfError naming `what` otherwise."""
    return read_value(xml_values.number, text, what)


# ---------------------------------------------------------------------------------------
# Data
# ---------------------------------------------------------------------------------------

@dataclass
class Inertial:
    mass: float
    origin_xyz: tuple = (0.0, 0.0, 0.0)
    origin_rpy: tuple = (0.0, 0.0, 0.0)
    ixx: float = 0.0
    ixy: float = 0.0
    ixz: float = 0.0
    iyy: float = 0.0
    iyz: float = 0.0
    izz: float = 0.0


@dataclass
class Geometry(Shape):
    """One <visual> or <collision>: its Shape (box, cylinder, sphere or mesh; a mesh's ``scale`` is
    (1, 1, 1) when not given), placed at ``origin_xyz``/``origin_rpy`` in its link. ``rgba`` only for
    visuals."""
    origin_xyz: tuple = (0.0, 0.0, 0.0)
    origin_rpy: tuple = (0.0, 0.0, 0.0)
    name: str = None
    material: str = None
    rgba: tuple = None


@dataclass
class UrdfLink:
    name: str
    inertial: Inertial = None
    collisions: list = field(default_factory=list)
    visuals: list = field(default_factory=list)


@dataclass
class Limit:
    lower: float = 0.0
    upper: float = 0.0
    effort: float = 0.0
    velocity: float = 0.0


@dataclass
class Dynamics:
    damping: float = 0.0
    friction: float = 0.0


@dataclass
class Mimic:
    """A joint's URDF <mimic>: its position is ``multiplier * position of joint + offset`` (urdfdom's defaults)."""
    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass
class UrdfJoint:
    name: str
    type: str
    parent: str
    child: str
    origin_xyz: tuple = (0.0, 0.0, 0.0)
    origin_rpy: tuple = (0.0, 0.0, 0.0)
    axis: tuple = (1.0, 0.0, 0.0)
    limit: Limit = None
    dynamics: Dynamics = None
    mimic: Mimic = None  # as written; RobotModel.mimics() gives the ones racebot drives


@dataclass
class Transmission:
    """``joints``: [(joint name, [interfaces])]; ``actuators``: [(name, [interfaces],
    mechanical reduction)].  Interfaces are normalised to ``hardware_interface/...``."""
    name: str
    type: str = ''
    joints: list = field(default_factory=list)
    actuators: list = field(default_factory=list)


@dataclass
class Rewrite:
    """One change sdformat's fixed-joint reduction made to an extension (sdf_reduction): ``element`` (a plugin
    parameter, 'reference', 'pose', 'contact/collision', ...) went from ``written`` (None: absent) to ``now``."""
    element: str
    written: str
    now: str


@dataclass
class GazeboPlugin:
    """A <plugin>: ``params`` maps each child tag to its text (the first one wins).
    ``element`` is the <plugin> element itself, for plugins that read nested elements. ``reference`` is the link
    of the enclosing <gazebo reference> (the link it was lumped into, if it was), or
    None. ``rewrites``: what sdformat's fixed-joint reduction changed (sdf_reduction)."""
    name: str
    filename: str
    params: dict = field(default_factory=dict)
    reference: str = None
    rewrites: list = field(default_factory=list)
    element: ET.Element = field(default=None, repr=False, compare=False)  # as written: nested blocks (a harness's)

    @property
    def robot_namespace(self) -> str | None:
        """``robotNamespace`` as written (may be ''), or None when absent: gazebo_ros_control
        then uses the model name."""
        return self.params.get('robotNamespace')

    @property
    def robot_param(self) -> str:
        return self.params.get('robotParam') or 'robot_description'

    @property
    def control_period(self) -> float | None:
        """``controlPeriod`` in seconds, or None (then: the physics step)."""
        text = self.params.get('controlPeriod')
        if text is None or text == '':
            return None
        value = number(text, 'plugin %r <controlPeriod>' % self.name)
        if value <= 0.0:
            raise UrdfError('plugin %r: <controlPeriod> must be > 0 seconds, got %s; give the '
                            'period, e.g. 0.001, or leave it out to use the physics step'
                            % (self.name, text))
        return value

    @property
    def is_ros_control(self) -> bool:
        """True for gazebo_ros_control's plugin, however the filename is spelt."""
        return library_key(self.filename) == 'gazebo_ros_control'


@dataclass
class RaySpec:
    samples: int = 640
    resolution: float = 1.0
    min_angle: float = 0.0
    max_angle: float = 0.0
    vertical_samples: int = 1
    vertical_resolution: float = 1.0
    vertical_min_angle: float = 0.0
    vertical_max_angle: float = 0.0
    range_min: float = 0.0
    range_max: float = 0.0
    range_resolution: float = 0.0
    noise_type: str = 'none'
    noise_mean: float = 0.0
    noise_stddev: float = 0.0


@dataclass
class CameraSpec:
    name: str = ''
    horizontal_fov: float = 1.047
    width: int = 320
    height: int = 240
    format: str = 'R8G8B8'
    clip_near: float = 0.1
    clip_far: float = 100.0
    noise_type: str = 'none'
    noise_mean: float = 0.0
    noise_stddev: float = 0.0
    pose: tuple = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # <camera><pose> in the sensor (a multicamera's cameras)
    distortion: tuple = (0.0, 0.0, 0.0, 0.0, 0.0)  # <distortion> k1, k2, k3, p1, p2 (Gazebo's lens model)


@dataclass
class ImuSpec:
    """The angular velocity and linear acceleration noise per axis (x, y, z), each (mean, stddev,
    bias_mean, bias_stddev) as Gazebo's ImuSensor reads <imu><angular_velocity><x><noise> (or the older
    <imu><noise><rate>/<accel>, one for all axes); zeros when none is given."""
    angular_velocity_noise: tuple = ((0.0, 0.0, 0.0, 0.0),) * 3
    linear_acceleration_noise: tuple = ((0.0, 0.0, 0.0, 0.0),) * 3


@dataclass
class GazeboElement:
    """An SDF element of a <gazebo> block that sdformat copies into the model or link and whose link names or
    pose its fixed-joint reduction rewrites (<light>, <projector>, <gripper>, <joint>); kept as written, for
    sdf_reduction. ``reference`` as GazeboPlugin's."""
    reference: str
    element: ET.Element
    rewrites: list = field(default_factory=list)


@dataclass
class SensorSpec:
    """A <sensor> of a <gazebo reference> block. ``reference``: the link Gazebo mounts it on (the block's link,
    or the link sdformat lumped that into, with ``pose`` then composed into that link: sdf_reduction);
    ``rewrites`` says what the reduction changed."""
    name: str
    type: str
    reference: str
    update_rate: float = 0.0
    always_on: bool = False
    visualize: bool = False
    pose: tuple = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    ray: RaySpec = None
    camera: CameraSpec = None
    imu: ImuSpec = None
    plugins: list = field(default_factory=list)
    cameras: list = field(default_factory=list)             # every <camera> (a multicamera has several)
    contact_collisions: list = field(default_factory=list)  # <contact><collision> names (contact sensors)
    rewrites: list = field(default_factory=list)


@dataclass
class RobotModel:
    name: str
    links: dict = field(default_factory=dict)
    joints: dict = field(default_factory=dict)
    transmissions: list = field(default_factory=list)
    plugins: list = field(default_factory=list)
    gazebo_refs: dict = field(default_factory=dict)  # <gazebo reference> properties, under the name written
    sensors: list = field(default_factory=list)
    gazebo_elements: list = field(default_factory=list)  # [GazeboElement]
    root_link: str = None
    materials: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    static: bool = False  # <gazebo><static> without reference, as sdformat reads it (urdf_extensions)

    def mimics(self) -> dict[str, Mimic]:
        """{joint: its Mimic} of the <mimic> joints racebot drives (beyond Gazebo 11, which ignores <mimic>): both
        the joint and the one it mimics move (not fixed, floating or planar). urdf_reader warns of the others and
        refuses loops."""
        movable = ('revolute', 'continuous', 'prismatic')
        return {j.name: j.mimic for j in self.joints.values()
                if j.mimic is not None and j.type in movable and j.mimic.joint in self.joints
                and self.joints[j.mimic.joint].type in movable}

    def child_joints(self, link: str) -> list[UrdfJoint]:
        """Joints whose parent is ``link``, in document order."""
        return [j for j in self.joints.values() if j.parent == link]

    def children(self, link: str) -> list[str]:
        """Names of the links attached below ``link``, in document order."""
        return [j.child for j in self.child_joints(link)]

    def parent_joint(self, link: str) -> UrdfJoint | None:
        """The joint whose child is ``link``; None for the root link."""
        return next((j for j in self.joints.values() if j.child == link), None)

    def fixed_joint_reduced(self, joint: UrdfJoint) -> bool:
        """sdformat's FixedJointShouldBeReduced: a fixed joint whose <gazebo reference> sets neither
        preserveFixedJoint nor disableFixedJointLumping."""
        ref = self.gazebo_refs.get(joint.name, {})
        return joint.type == 'fixed' and not any(ref.get(key) is True for key in KEEP_FIXED_JOINT)

    def fixed_parent_chain(self, link: str) -> list[UrdfJoint]:
        """The fixed joints from ``link`` up to the link Gazebo merges it into.

        Gazebo lumps a link hanging on fixed joints into the nearest ancestor that is the root
        or hangs on a moving joint (unless the joint's <gazebo reference> sets
        preserveFixedJoint or disableFixedJointLumping).  Returns the joints child-first;
        empty when ``link`` is not merged.
        """
        if link not in self.links:
            raise KeyError('robot %r has no link %r' % (self.name, link))
        chain = []
        joint = self.parent_joint(link)
        while joint is not None and self.fixed_joint_reduced(joint):
            chain.append(joint)
            joint = self.parent_joint(joint.parent)
        return chain

    def lumped_link(self, link: str) -> str:
        """The link that ``link`` is merged into (``link`` itself when it is not merged)."""
        chain = self.fixed_parent_chain(link)
        return chain[-1].parent if chain else link

    def pose_in_lumped_link(self, link: str) -> Transform:
        """``(xyz, quaternion xyzw)`` of ``link``'s frame in its lumped link's frame."""
        transform = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        for joint in reversed(self.fixed_parent_chain(link)):
            transform = compose(transform, joint.origin_xyz + joint.origin_rpy)
        return transform



def normalise_interface(name: str) -> str:
    """``EffortJointInterface`` -> ``hardware_interface/EffortJointInterface``."""
    name = (name or '').strip()
    return name if '/' in name or not name else 'hardware_interface/' + name


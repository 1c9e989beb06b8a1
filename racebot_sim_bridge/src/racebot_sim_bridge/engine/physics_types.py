"""The engine's value types: what World, Model, Link and Joint hand out and take, and the error they raise.

No ROS here, no PyBullet call. Kept apart from physics.py, model.py, link.py and joint.py so that each of
them can name these without importing another (physics.py re-exports them for callers).
"""
from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass
from enum import Enum

JointState = namedtuple('JointState', 'position velocity')
Pose = namedtuple('Pose', 'position orientation')  # xyz, quaternion xyzw
Twist = namedtuple('Twist', 'linear angular')
LinkDynamics = namedtuple('LinkDynamics', 'mass inertia_diagonal inertial_position inertial_orientation')


class PhysicsError(RuntimeError):
    """A request the physics world cannot carry out; the message says why."""


class BodyKind(str, Enum):
    """What a body was built from: a URDF (a robot, one PyBullet body) or an SDF model (a body per link)."""
    URDF = 'urdf'
    SDF = 'sdf'

    def __str__(self):
        return self.value


@dataclass(frozen=True)
class BodySource:
    """What a body was built from, all another client needs to build a copy (picklable: the viewer and
    the render worker get it through a pipe). kind SDF: `model` is the sdf_model.SdfModel; kind URDF:
    `model` is the urdf_model.RobotModel and `urdf_xml` its URDF, meshes resolved to files."""
    kind: BodyKind
    model: object
    urdf_xml: str = None

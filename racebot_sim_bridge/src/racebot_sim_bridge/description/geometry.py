"""The shape of a collision or visual: one type for URDF links (urdf_model.Geometry, a Shape with its origin)
and SDF links (sdf_model.Collision and Visual hold one), so that the physics and the sensors build from
either alike."""
from dataclasses import dataclass
from enum import Enum

__all__ = ['Shape', 'ShapeKind']


class ShapeKind(str, Enum):
    """A shape's geometry element. A str: it compares equal to the element's tag ('box' == ShapeKind.BOX)."""
    BOX = 'box'
    CYLINDER = 'cylinder'
    SPHERE = 'sphere'
    PLANE = 'plane'
    MESH = 'mesh'

    def __str__(self):
        return self.value


@dataclass
class Shape:
    """box: ``size`` (x, y, z); cylinder: ``radius``, ``length`` (along z); sphere: ``radius``; plane (SDF
    only): unit ``normal`` and ``size`` (x, y), infinite for physics; mesh: ``filename`` and ``scale``
    (x, y, z). An SDF mesh's ``filename`` is the absolute path of the converted OBJ in the mesh cache (so
    that any process can build it) and ``uri`` the URI as written, for messages; a URDF mesh's ``filename``
    is as written until urdf_assets resolves it."""
    kind: ShapeKind
    size: tuple = None
    radius: float = None
    length: float = None
    normal: tuple = None
    filename: str = None
    scale: tuple = None
    uri: str = None

    def __post_init__(self):
        self.kind = ShapeKind(self.kind)  # the readers pass the element's tag

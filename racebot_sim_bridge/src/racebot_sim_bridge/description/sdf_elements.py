"""The pieces of an SDF read with warnings: values, poses, shapes (meshes resolved and converted) and colours.

Pure Python: no rospy, no pybullet. ElementReader is the part of sdf_reader's world reader that reads one
element's values; the readers of links (sdf_links), models (sdf_models) and the world (sdf_reader) add the
structure. A value that cannot be used raises Unusable, caught where the element holding it is skipped with one
warning; the checks are xml_values' (as the URDF reader's are), the wording this format's.
"""
from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from typing import NamedTuple

from racebot_sim_bridge.description import meshes, model_path, xml_values
from racebot_sim_bridge.description.geometry import Shape
from racebot_sim_bridge.description.materials import Rgba, gazebo_material_rgba
from racebot_sim_bridge.description.sdf_model import ZERO_POSE
from racebot_sim_bridge.kinematics.rotations import XyzRpy

__all__ = ['Unusable', 'ElementReader', 'floats', 'child_float', 'child_bool', 'quote']


class Unusable(Exception):
    """A value written in the file cannot be used (non-numeric, non-finite, out of range); the message
    says which and why.  Raised by the value readers (floats, child_float, child_bool, pose, the
    size checks), caught where the element holding the value is skipped with one warning."""

    # How an SDF words an xml_values.BadValue about `what` (the text as written, stripped).
    _WORDING = {
        xml_values.Problem.COUNT: '%(what)s needs %(count)d numbers, got %(text)r',
        xml_values.Problem.NUMBER: '%(what)s must be numbers, got %(text)r',
        xml_values.Problem.FINITE: '%(what)s must be finite, got %(text)r',
        xml_values.Problem.BOOLEAN: '%(what)s must be true or false, got %(text)r',
    }

    @classmethod
    def of(cls, bad: xml_values.BadValue, what: str) -> Unusable:
        """The Unusable of an xml_values.BadValue found in `what`."""
        return cls(cls._WORDING[bad.problem] % {'what': what, 'text': (bad.text or '').strip(), 'count': bad.count})


class _Geometry(NamedTuple):
    """A usable <geometry>: its Shape and the colour its mesh file gives (None: a primitive, or a mesh
    without one)."""
    shape: Shape
    mesh_rgba: tuple = None


class _MeshFile(NamedTuple):
    """A mesh URI read once (per folder it is relative to): the converted file and its colour, or
    `problem` (why it cannot be used; warned about the first time only)."""
    obj_path: str = None
    rgba: tuple = None
    problem: str = None


_UNSUPPORTED_GEOMETRY = {
    'heightmap': 'heightmap geometry is not supported',
    'polyline': 'polyline geometry is not supported; use boxes',
    'image': 'image geometry is not supported',
    'capsule': 'capsule geometry is not part of SDF 1.6; use a cylinder',
    'ellipsoid': 'ellipsoid geometry is not part of SDF 1.6; use a sphere',
    'empty': 'empty geometry has nothing to simulate',
}


def _read_value(read, text, what, *args):
    """read(text, *args), one of xml_values' readers; its BadValue raised as the Unusable about `what`."""
    try:
        return read(text, *args)
    except xml_values.BadValue as bad:
        raise Unusable.of(bad, what) from None


def floats(text: str | None, count: int, what: str) -> tuple[float, ...]:
    """``count`` finite floats from whitespace-separated ``text``, else ``Unusable``."""
    return _read_value(xml_values.numbers, text, what, count)


def child_float(elem: ET.Element, tag: str, default: float | None, what: str) -> float | None:
    child = elem.find(tag)
    if child is None:
        return default
    return floats(child.text, 1, what)[0]


def child_bool(elem: ET.Element, tag: str, default: bool, what: str) -> bool:
    child = elem.find(tag)
    if child is None:
        return default
    return _read_value(xml_values.boolean, child.text, what)


def quote(name: str) -> str:
    return "'%s'" % name


class ElementReader:
    """Reads the values of SDF elements, warning (into ``warnings``) about what it cannot use. ``source``
    names the document; ``search`` is the model path for model:// URIs (default: looked up on first use)."""

    def __init__(self, source: str, search: list[str] | None = None) -> None:
        self.source = source
        self.warnings = []
        self._search = search  # the model path, looked up on first use (it lists ROS packages)
        # relative mesh URIs: relative to the folder of the model being read, else the world file's
        self.base_dir = os.path.dirname(source) if os.path.isfile(source) else None
        self._meshes = {}  # (uri, base_dir) -> _MeshFile: each mesh read and warned about once

    @property
    def search(self) -> list[str]:
        if self._search is None:
            self._search = model_path.model_path()
        return self._search

    def warn(self, where: str, message: str) -> None:
        self.warnings.append('%s: %s' % (where, message) if where else message)

    def skipped(self, where: str, problem: str | Exception) -> None:
        """Warns that the element at `where` is skipped because of `problem`; returns None, its value."""
        self.warn(where, '%s; skipped' % problem)
        return None

    def unsupported(self, where: str, child: ET.Element, reasons: dict[str, str]) -> None:
        """Warns that `child` is skipped for its tag's reason in `reasons`."""
        self.warn(where, '<%s> %s: %s; skipped' % (child.tag, quote(child.get('name', '')), reasons[child.tag]))

    # -- small pieces -----------------------------------------------------------------

    def pose(self, elem: ET.Element, where: str) -> XyzRpy:
        """The <pose> child of ``elem`` as a 6-tuple (zeros when absent)."""
        child = elem.find('pose')
        if child is None:
            return ZERO_POSE
        frame = child.get('frame') or child.get('relative_to')
        if frame:
            self.warn(where, "pose frame %s is not supported; the pose is taken relative to "
                             "the parent" % quote(frame))
        if not (child.text or '').strip():
            return ZERO_POSE
        return floats(child.text, 6, 'pose')

    def shape(self, geometry: ET.Element | None, where: str) -> _Geometry | None:
        """The _Geometry of a <geometry>, or None when it cannot be simulated: warned about here, once
        (a mesh that failed for an earlier element is not warned about again)."""
        if geometry is None:
            self.warn(where, 'no <geometry>; skipped')
            return None
        kinds = list(geometry)
        if not kinds:
            self.warn(where, 'empty <geometry>; skipped')
            return None
        if len(kinds) > 1:
            self.warn(where, 'several shapes in one <geometry> (%s); only the first is used'
                      % ', '.join(k.tag for k in kinds))
        elem = kinds[0]
        kind = elem.tag
        if kind not in ('box', 'cylinder', 'sphere', 'plane', 'mesh'):
            return self.skipped(where, _UNSUPPORTED_GEOMETRY.get(kind, 'unknown geometry <%s>' % kind))
        try:
            return self.mesh(elem, where) if kind == 'mesh' else _Geometry(self.primitive(elem))
        except Unusable as err:
            return self.skipped(where, err)

    def primitive(self, elem: ET.Element) -> Shape:
        """The Shape of a <box>, <cylinder>, <sphere> or <plane>; Unusable naming a value that is not usable."""
        kind = elem.tag
        if kind == 'box':
            size_elem = elem.find('size')
            size = (1.0, 1.0, 1.0) if size_elem is None else floats(size_elem.text, 3, 'box size')
            self._positive(size, 'box size')
            return Shape('box', size=size)
        if kind == 'cylinder':
            radius = child_float(elem, 'radius', 1.0, 'cylinder radius')
            length = child_float(elem, 'length', 1.0, 'cylinder length')
            self._positive((radius,), 'cylinder radius')
            self._positive((length,), 'cylinder length')
            return Shape('cylinder', radius=radius, length=length)
        if kind == 'sphere':
            radius = child_float(elem, 'radius', 1.0, 'sphere radius')
            self._positive((radius,), 'sphere radius')
            return Shape('sphere', radius=radius)
        normal_elem, size_elem = elem.find('normal'), elem.find('size')
        normal = (0.0, 0.0, 1.0) if normal_elem is None else floats(normal_elem.text, 3, 'plane normal')
        norm = math.sqrt(sum(c * c for c in normal))
        if norm == 0.0:
            raise Unusable('degenerate geometry: plane normal is the zero vector')
        size = (1.0, 1.0) if size_elem is None else floats(size_elem.text, 2, 'plane size')
        self._positive(size, 'plane size')
        return Shape('plane', size=size, normal=tuple(c / norm for c in normal))

    def mesh(self, elem: ET.Element, where: str) -> _Geometry | None:
        """The _Geometry of a <mesh>, its file resolved and converted (meshes.convert); None when the
        file cannot be used: warned about (naming the URI and where it was looked for) the first
        time only. Unusable for an unusable value (no URI, a bad scale)."""
        uri = (elem.findtext('uri') or '').strip()
        if not uri:
            raise Unusable('a <mesh> without <uri>; give <uri>model://NAME/meshes/FILE.dae</uri>')
        scale_elem = elem.find('scale')
        scale = (1.0, 1.0, 1.0) if scale_elem is None else floats(scale_elem.text, 3, 'mesh scale')
        self._positive(tuple(abs(c) for c in scale), 'mesh scale')
        if elem.find('submesh') is not None:
            self.warn('', 'mesh %s: <submesh> is not supported; the whole mesh is used' % uri)
        key = (uri, self.base_dir)
        known = self._meshes.get(key)
        if known is None:
            known = self._meshes[key] = self._read_mesh(uri)
            if known.problem is not None:
                return self.skipped(where, known.problem)
        if known.problem is not None:
            return None  # warned about when it was first read
        return _Geometry(Shape('mesh', filename=known.obj_path, scale=scale, uri=uri), known.rgba)

    def _read_mesh(self, uri):
        """The _MeshFile of a mesh URI (relative ones: to the current base folder)."""
        try:
            path = model_path.resolve_uri(uri, self.base_dir, self.search if uri.startswith('model://') else None)
            converted = meshes.convert(path)
        except (model_path.ResolveError, meshes.MeshError) as err:
            return _MeshFile(problem=str(err))
        return _MeshFile(converted.obj_path, converted.rgba)

    @staticmethod
    def _positive(values, what):
        if not all(v > 0.0 for v in values):
            raise Unusable('degenerate geometry: %s must be > 0, got %s'
                           % (what, ' '.join('%g' % v for v in values)))

    @staticmethod
    def rgba(material: ET.Element | None) -> Rgba | None:
        if material is None:
            return None
        for tag in ('diffuse', 'ambient'):
            child = material.find(tag)
            if child is not None and (child.text or '').strip():
                parts = child.text.split()
                values = floats(child.text, len(parts) if len(parts) in (3, 4) else 4,
                                'material %s colour' % tag)
                return values if len(values) == 4 else values + (1.0,)
        script = material.find('script/name')
        if script is not None:
            return gazebo_material_rgba(script.text)
        return None


"""Read SDF 1.6 world files into plain dataclasses.

Pure Python: no rospy, no pybullet.  ``physics.py`` turns the result into bodies.

What is understood: the world's physics block and gravity; models made of links with box,
cylinder, sphere, plane and mesh geometry, their poses, masses, inertias, ODE friction (mu, mu2)
and visual colours (explicit or Gazebo material script names); ``<include>`` of models from the
Gazebo model path (model_path.py: GAZEBO_MODEL_PATH, packages' gazebo_model_path exports,
~/.gazebo/models; model.config picks the SDF file) with the include's name, pose and static,
``model://ground_plane`` and ``model://sun`` built in as Gazebo ships them; the first ``<state>``
block's model and link poses, which Gazebo applies when it loads a saved world.  Mesh URIs
(model://, package://, file://, paths) are resolved and the files converted here
(meshes.convert), so a parsed world names only absolute files and needs no search path again.

A model's joints (revolute, prismatic, fixed), its ``<plugin>``s and its links' ``<sensor>``s are
kept (plugins and sensors as the XML written): such a model is a robot, spawned through the URDF
path (sdf_urdf.py).  Everything else that matters to the physics (heightmap and polyline
geometry, world plugins, nested models, includes inside models, actors) is skipped with ONE entry in
``World.warnings`` naming the element, where it is and why; so are elements whose values are
unusable (non-numeric, non-finite, zero or negative sizes) and models or meshes that cannot be
found (the warning names the URI and every place searched) or read.  Only a missing file, text
that is not XML and a document without ``<world>`` raise ``WorldError``.

Poses are 6-tuples ``(x, y, z, roll, pitch, yaw)`` as SDF writes them; the maths on them (and
their conventions) is rotations.py's.
"""

import math
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import NamedTuple

__all__ = [
    'WorldError', 'World', 'Physics', 'Light', 'sun_light', 'Model', 'Link', 'Joint', 'Collision', 'Visual', 'Shape',
    'parse_world', 'load_world', 'GAZEBO_MATERIALS', 'EMPTY_WORLD_SDF', 'ZERO_POSE',
]

from racebot_sim_bridge.description import meshes, model_path
from racebot_sim_bridge.description.materials import GAZEBO_MATERIALS, gazebo_material_rgba  # re-exported
from racebot_sim_bridge.kinematics.rotations import as_xyz_rpy, compose, inverse

ZERO_POSE = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)

# What Gazebo's worlds/empty.world holds, for world_name:=worlds/empty.world (the default of
# empty_world.launch), which Gazebo finds in its own resource path.
EMPTY_WORLD_SDF = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="default">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
  </world>
</sdf>
"""

_EMPTY_WORLD_NAMES = ('worlds/empty.world', 'empty.world')


class WorldError(ValueError):
    """The world cannot be read at all (missing file, not XML, no <world>)."""


# ---------------------------------------------------------------------------------------
# Data
# ---------------------------------------------------------------------------------------

@dataclass
class Physics:
    """The physics block, with Gazebo's defaults."""
    type: str = 'ode'
    max_step_size: float = 0.001
    real_time_factor: float = 1.0
    real_time_update_rate: float = 1000.0
    gravity: tuple = (0.0, 0.0, -9.8)


@dataclass
class Shape:
    """Geometry.  box: ``size`` (x, y, z); cylinder: ``radius``, ``length`` (along z);
    sphere: ``radius``; plane: unit ``normal`` and ``size`` (x, y), infinite for physics;
    mesh: ``filename`` (the absolute path of the converted OBJ in the mesh cache, so that any
    process can build it), ``scale`` (x, y, z) and ``uri`` (as written, for messages)."""
    kind: str
    size: tuple = None
    radius: float = None
    length: float = None
    normal: tuple = None
    filename: str = None
    scale: tuple = None
    uri: str = None


@dataclass
class Collision:
    name: str
    pose: tuple
    shape: Shape
    mu: float = None
    mu2: float = None
    laser_retro: float = 0.0  # what a laser ray that hits it reads as intensity (Gazebo's <laser_retro>)


@dataclass
class Visual:
    name: str
    pose: tuple
    shape: Shape
    rgba: tuple = None


@dataclass
class Link:
    """A link.  ``mass`` is SDF's default 1.0 when no <inertial> gives one; ``inertia`` is
    ``(ixx, ixy, ixz, iyy, iyz, izz)`` about ``inertial_pose``, or None when not given."""
    name: str
    pose: tuple = ZERO_POSE
    mass: float = 1.0
    inertia: tuple = None
    inertial_pose: tuple = ZERO_POSE
    collisions: list = field(default_factory=list)
    visuals: list = field(default_factory=list)
    sensors: list = field(default_factory=list)  # each <sensor> element as written (XML text)


# SDF's "no limit": <limit> defaults of lower/upper (+-1e16) and of effort/velocity (-1)
UNLIMITED = 1e16


@dataclass
class Joint:
    """A joint.  ``pose`` is the joint frame in the child link's frame (SDF 1.6); ``axis`` is in that
    frame, or in the model's when ``axis_in_model`` (<use_parent_model_frame> or expressed_in
    __model__).  ``type`` is revolute, prismatic or fixed; limits are SDF's (``lower``/``upper`` of
    magnitude UNLIMITED and negative ``effort``/``velocity`` mean none)."""
    name: str
    type: str
    parent: str
    child: str
    pose: tuple = ZERO_POSE
    axis: tuple = (0.0, 0.0, 1.0)
    axis_in_model: bool = False
    lower: float = -UNLIMITED
    upper: float = UNLIMITED
    effort: float = -1.0
    velocity: float = -1.0
    damping: float = 0.0
    friction: float = 0.0


@dataclass
class Model:
    name: str
    pose: tuple = ZERO_POSE
    static: bool = False
    links: list = field(default_factory=list)
    joints: list = field(default_factory=list)
    plugins: list = field(default_factory=list)  # each <plugin> element as written (XML text)

    @property
    def is_robot(self):
        """Joints, plugins or sensors: what only the URDF path (sdf_urdf.py) simulates."""
        return bool(self.joints or self.plugins or any(link.sensors for link in self.links))

    def link(self, name):
        """The link called ``name``; KeyError naming the model's links otherwise."""
        for link in self.links:
            if link.name == name:
                return link
        raise KeyError('model %r has no link %r (links: %s)'
                       % (self.name, name, ', '.join(lk.name for lk in self.links) or 'none'))

    def world_pose_of(self, link, element=None):
        """World pose ``(xyz, quaternion xyzw)`` of a link, or of a collision or visual of
        it when ``element`` is given.  ``link`` is a Link or a link name."""
        if isinstance(link, str):
            link = self.link(link)
        transform = compose(self.pose, link.pose)
        if element is not None:
            transform = compose(transform, element.pose)
        return transform


@dataclass
class Light:
    """A world <light>, SDF 1.6's defaults. ``pose`` is a 6-tuple in the world; colours are rgba;
    ``attenuation``: (range, constant, linear, quadratic). Nothing is lit by it here: it is world
    state that gazebo_ros's light services read, change and delete."""
    name: str
    type: str = 'point'
    cast_shadows: bool = False
    pose: tuple = ZERO_POSE
    diffuse: tuple = (1.0, 1.0, 1.0, 1.0)
    specular: tuple = (0.1, 0.1, 0.1, 1.0)
    attenuation: tuple = (10.0, 1.0, 1.0, 0.0)
    direction: tuple = (0.0, 0.0, -1.0)


def sun_light(name='sun', pose=None):
    """Gazebo's model://sun: one directional light (its model.sdf's values)."""
    return Light(name, 'directional', True, pose or (0.0, 0.0, 10.0, 0.0, 0.0, 0.0), (0.8, 0.8, 0.8, 1.0),
                 (0.2, 0.2, 0.2, 1.0), (1000.0, 0.9, 0.01, 0.001), (-0.5, 0.1, -0.9))


@dataclass
class World:
    name: str = 'default'
    physics: Physics = field(default_factory=Physics)
    models: list = field(default_factory=list)
    lights: list = field(default_factory=list)
    warnings: list = field(default_factory=list)
    source: str = '<string>'

    def model(self, name):
        """The model called ``name``; KeyError naming the world's models otherwise."""
        for model in self.models:
            if model.name == name:
                return model
        raise KeyError('world %r has no model %r (models: %s)'
                       % (self.name, name, ', '.join(m.name for m in self.models) or 'none'))


# ---------------------------------------------------------------------------------------
# Parsing
# ---------------------------------------------------------------------------------------

class _Unusable(Exception):
    """A value written in the file cannot be used (non-numeric, non-finite, out of range); the message
    says which and why.  Raised by the value readers (_floats, _child_float, _child_bool, pose, the
    size checks), caught where the element holding the value is skipped with one warning."""


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


class _ModelFolder(NamedTuple):
    """Where an <include>d model is: `path`, or None and `problem` (what is wrong, what to do).
    `missing`: the model is on no folder of the model path; such includes are warned about once per
    URI, all together, after the world is read."""
    path: str = None
    problem: str = None
    missing: bool = False


_UNSUPPORTED_GEOMETRY = {
    'heightmap': 'heightmap geometry is not supported',
    'polyline': 'polyline geometry is not supported; use boxes',
    'image': 'image geometry is not supported',
    'capsule': 'capsule geometry is not part of SDF 1.6; use a cylinder',
    'ellipsoid': 'ellipsoid geometry is not part of SDF 1.6; use a sphere',
    'empty': 'empty geometry has nothing to simulate',
}
_WORLD_SILENT = {'physics', 'gravity', 'light', 'gui', 'scene', 'spherical_coordinates',
                 'magnetic_field', 'atmosphere', 'wind', 'audio', 'state', 'model', 'include'}
_WORLD_UNSUPPORTED = {
    'actor': 'actors (animated people) are not supported',
    'plugin': 'world plugins are not supported',
    'road': 'roads are not supported',
    'population': 'populations are not supported; write the models out',
    'frame': 'frames are not supported',
}
_MODEL_UNSUPPORTED = {
    'model': 'nested models are not supported; move it to the world level',
    'include': 'includes inside a model are not supported',
    'gripper': 'grippers are not supported',
}
_LINK_UNSUPPORTED = {
    'projector': 'projectors are not supported',
    'light': 'lights are not simulated',
    'audio_source': 'audio is not supported',
    'audio_sink': 'audio is not supported',
    'battery': 'batteries are not supported',
    'particle_emitter': 'particle emitters are not supported',
}


def _floats(text, count, what):
    """``count`` finite floats from whitespace-separated ``text``, else ``_Unusable``."""
    parts = (text or '').split()
    if len(parts) != count:
        raise _Unusable('%s needs %d numbers, got %r' % (what, count, (text or '').strip()))
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        raise _Unusable('%s must be numbers, got %r' % (what, text.strip())) from None
    if not all(math.isfinite(v) for v in values):
        raise _Unusable('%s must be finite, got %r' % (what, text.strip()))
    return values


def _child_float(elem, tag, default, what):
    child = elem.find(tag)
    if child is None:
        return default
    return _floats(child.text, 1, what)[0]


def _child_bool(elem, tag, default, what):
    child = elem.find(tag)
    if child is None:
        return default
    text = (child.text or '').strip().lower()
    if text in ('true', '1'):
        return True
    if text in ('false', '0'):
        return False
    raise _Unusable('%s must be true or false, got %r' % (what, (child.text or '').strip()))


def _quote(name):
    return "'%s'" % name


class _WorldReader:
    def __init__(self, source, search=None):
        self.source = source
        self.warnings = []
        self._search = search  # the model path, looked up on first use (it lists ROS packages)
        # relative mesh URIs: relative to the folder of the model being read, else the world file's
        self.base_dir = os.path.dirname(source) if os.path.isfile(source) else None
        self._meshes = {}  # (uri, base_dir) -> _MeshFile: each mesh read and warned about once
        self._missing_models = {}  # model:// URI -> [message, names of the includes skipped]

    @property
    def search(self):
        if self._search is None:
            self._search = model_path.model_path()
        return self._search

    def warn(self, where, message):
        self.warnings.append('%s: %s' % (where, message) if where else message)

    def skipped(self, where, problem):
        """Warns that the element at `where` is skipped because of `problem`; returns None, its value."""
        self.warn(where, '%s; skipped' % problem)
        return None

    # -- small pieces -----------------------------------------------------------------

    def pose(self, elem, where):
        """The <pose> child of ``elem`` as a 6-tuple (zeros when absent)."""
        child = elem.find('pose')
        if child is None:
            return ZERO_POSE
        frame = child.get('frame') or child.get('relative_to')
        if frame:
            self.warn(where, "pose frame %s is not supported; the pose is taken relative to "
                             "the parent" % _quote(frame))
        if not (child.text or '').strip():
            return ZERO_POSE
        return _floats(child.text, 6, 'pose')

    def shape(self, geometry, where):
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
        except _Unusable as err:
            return self.skipped(where, err)

    def primitive(self, elem):
        """The Shape of a <box>, <cylinder>, <sphere> or <plane>; _Unusable naming a value that is not usable."""
        kind = elem.tag
        if kind == 'box':
            size_elem = elem.find('size')
            size = (1.0, 1.0, 1.0) if size_elem is None else _floats(size_elem.text, 3,
                                                                      'box size')
            self._positive(size, 'box size')
            return Shape('box', size=size)
        if kind == 'cylinder':
            radius = _child_float(elem, 'radius', 1.0, 'cylinder radius')
            length = _child_float(elem, 'length', 1.0, 'cylinder length')
            self._positive((radius,), 'cylinder radius')
            self._positive((length,), 'cylinder length')
            return Shape('cylinder', radius=radius, length=length)
        if kind == 'sphere':
            radius = _child_float(elem, 'radius', 1.0, 'sphere radius')
            self._positive((radius,), 'sphere radius')
            return Shape('sphere', radius=radius)
        normal_elem, size_elem = elem.find('normal'), elem.find('size')
        normal = (0.0, 0.0, 1.0) if normal_elem is None else _floats(normal_elem.text, 3,
                                                                      'plane normal')
        norm = math.sqrt(sum(c * c for c in normal))
        if norm == 0.0:
            raise _Unusable('degenerate geometry: plane normal is the zero vector')
        size = (1.0, 1.0) if size_elem is None else _floats(size_elem.text, 2, 'plane size')
        self._positive(size, 'plane size')
        return Shape('plane', size=size, normal=tuple(c / norm for c in normal))

    def mesh(self, elem, where):
        """The _Geometry of a <mesh>, its file resolved and converted (meshes.convert); None when the
        file cannot be used: warned about (naming the URI and where it was looked for) the first
        time only. _Unusable for an unusable value (no URI, a bad scale)."""
        uri = (elem.findtext('uri') or '').strip()
        if not uri:
            raise _Unusable('a <mesh> without <uri>; give <uri>model://NAME/meshes/FILE.dae</uri>')
        scale_elem = elem.find('scale')
        scale = (1.0, 1.0, 1.0) if scale_elem is None else _floats(scale_elem.text, 3, 'mesh scale')
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
            raise _Unusable('degenerate geometry: %s must be > 0, got %s'
                            % (what, ' '.join('%g' % v for v in values)))

    @staticmethod
    def rgba(material):
        if material is None:
            return None
        for tag in ('diffuse', 'ambient'):
            child = material.find(tag)
            if child is not None and (child.text or '').strip():
                parts = child.text.split()
                values = _floats(child.text, len(parts) if len(parts) in (3, 4) else 4,
                                 'material %s colour' % tag)
                return values if len(values) == 4 else values + (1.0,)
        script = material.find('script/name')
        if script is not None:
            return gazebo_material_rgba(script.text)
        return None

    # -- elements ---------------------------------------------------------------------

    def collision(self, elem, where):
        name = elem.get('name', '')
        where = '%s collision %s' % (where, _quote(name))
        try:
            pose = self.pose(elem, where)
        except _Unusable as err:
            return self.skipped(where, err)
        geometry = self.shape(elem.find('geometry'), where)
        if geometry is None:
            return None
        mu = mu2 = None
        ode = elem.find('surface/friction/ode')
        if ode is not None:
            try:
                mu = _child_float(ode, 'mu', None, 'friction mu')
                mu2 = _child_float(ode, 'mu2', None, 'friction mu2')
            except _Unusable as err:
                return self.skipped(where, err)
            for label, value in (('mu', mu), ('mu2', mu2)):
                if value is not None and value < 0.0:
                    return self.skipped(where, 'friction %s must be >= 0, got %g' % (label, value))
        try:
            retro = _child_float(elem, 'laser_retro', 0.0, 'laser_retro')
        except _Unusable as err:
            return self.skipped(where, err)
        return Collision(name, pose, geometry.shape, mu, mu2, retro)

    def visual(self, elem, where):
        name = elem.get('name', '')
        where = '%s visual %s' % (where, _quote(name))
        try:
            pose = self.pose(elem, where)
        except _Unusable as err:
            return self.skipped(where, err)
        geometry = self.shape(elem.find('geometry'), where)
        if geometry is None:
            return None
        try:
            # an SDF <material> overrides the mesh's own, as in Gazebo
            rgba = self.rgba(elem.find('material')) or geometry.mesh_rgba
        except _Unusable as err:
            return self.skipped(where, err)
        return Visual(name, pose, geometry.shape, rgba)

    def link(self, elem, where, static=False):
        name = elem.get('name')
        if not name:
            self.warn(where, 'a <link> without a name; skipped')
            return None
        where = '%s link %s' % (where, _quote(name))
        try:
            link = Link(name, pose=self.pose(elem, where))
            inertial = elem.find('inertial')
            if inertial is not None:
                mass = _child_float(inertial, 'mass', 1.0, 'mass')
                if mass > 0.0:
                    link.mass = mass
                elif not static:  # a static link's mass does not matter
                    self.warn(where, 'mass must be > 0, got %g; using 1.0 (the SDF default)'
                              % mass)
                link.inertial_pose = self.pose(inertial, where + ' inertial')
                inertia = inertial.find('inertia')
                if inertia is not None:
                    defaults = {'ixx': 1.0, 'ixy': 0.0, 'ixz': 0.0,
                                'iyy': 1.0, 'iyz': 0.0, 'izz': 1.0}
                    link.inertia = tuple(_child_float(inertia, key, default, key)
                                         for key, default in defaults.items())
        except _Unusable as err:
            return self.skipped(where, err)
        for child in elem:
            if child.tag == 'collision':
                collision = self.collision(child, where)
                if collision is not None:
                    link.collisions.append(collision)
            elif child.tag == 'visual':
                visual = self.visual(child, where)
                if visual is not None:
                    link.visuals.append(visual)
            elif child.tag == 'sensor':
                link.sensors.append(ET.tostring(child, encoding='unicode'))
            elif child.tag in _LINK_UNSUPPORTED:
                self.warn(where, '<%s> %s: %s; skipped' % (
                    child.tag, _quote(child.get('name', '')), _LINK_UNSUPPORTED[child.tag]))
        return link

    def joint(self, elem, where):
        """A <joint>; None (warned) when unusable.  ball, universal, revolute2, screw and gearbox
        joints are not simulated: made fixed, with a warning, so that the links stay joined."""
        name = elem.get('name')
        if not name:
            return self.skipped(where, 'a <joint> without a name')
        where = '%s joint %s' % (where, _quote(name))
        kind = elem.get('type', '')
        parent, child = (elem.findtext('parent') or '').strip(), (elem.findtext('child') or '').strip()
        if not parent or not child:
            return self.skipped(where, 'a joint needs <parent> and <child> link names')
        if kind not in ('revolute', 'prismatic', 'fixed'):
            if kind not in ('ball', 'universal', 'revolute2', 'screw', 'gearbox'):
                return self.skipped(where, 'unknown joint type %s (SDF has revolute, prismatic, fixed, ball, '
                                    'universal, revolute2, screw, gearbox)' % _quote(kind))
            self.warn(where, '%s joints are not supported; made fixed' % kind)
            kind = 'fixed'
        try:
            joint = Joint(name, kind, parent, child, pose=self.pose(elem, where))
            axis = elem.find('axis')
            if axis is not None and kind != 'fixed':
                xyz = axis.find('xyz')
                if xyz is not None:
                    joint.axis = _floats(xyz.text, 3, 'axis xyz')
                    joint.axis_in_model = xyz.get('expressed_in') == '__model__'
                joint.axis_in_model = _child_bool(axis, 'use_parent_model_frame', joint.axis_in_model,
                                                  'use_parent_model_frame')
                if not any(joint.axis):
                    raise _Unusable('axis xyz is the zero vector; give the direction the joint moves along')
                limit = axis.find('limit')
                if limit is not None:
                    joint.lower = _child_float(limit, 'lower', -UNLIMITED, 'limit lower')
                    joint.upper = _child_float(limit, 'upper', UNLIMITED, 'limit upper')
                    joint.effort = _child_float(limit, 'effort', -1.0, 'limit effort')
                    joint.velocity = _child_float(limit, 'velocity', -1.0, 'limit velocity')
                    if joint.lower > joint.upper:
                        raise _Unusable('limit lower %g is above upper %g' % (joint.lower, joint.upper))
                dynamics = axis.find('dynamics')
                if dynamics is not None:
                    joint.damping = _child_float(dynamics, 'damping', 0.0, 'dynamics damping')
                    joint.friction = _child_float(dynamics, 'friction', 0.0, 'dynamics friction')
                    if joint.damping < 0 or joint.friction < 0:
                        raise _Unusable('dynamics damping and friction must be >= 0, got %g and %g'
                                        % (joint.damping, joint.friction))
        except _Unusable as err:
            return self.skipped(where, err)
        return joint

    def model(self, elem):
        name = elem.get('name')
        if not name:
            self.warn('world', 'a <model> without a name; skipped')
            return None
        where = 'model %s' % _quote(name)
        try:
            model = Model(name, pose=self.pose(elem, where),
                          static=_child_bool(elem, 'static', False, 'static'))
        except _Unusable as err:
            return self.skipped(where, err)
        warnings_before = len(self.warnings)
        for child in elem:
            if child.tag == 'link':
                link = self.link(child, where, model.static)
                if link is None:
                    continue
                if any(other.name == link.name for other in model.links):
                    self.warn(where, 'a second link %s; skipped' % _quote(link.name))
                    continue
                model.links.append(link)
            elif child.tag == 'joint':
                joint = self.joint(child, where)
                if joint is not None:
                    model.joints.append(joint)
            elif child.tag == 'plugin':
                model.plugins.append(ET.tostring(child, encoding='unicode'))
            elif child.tag in _MODEL_UNSUPPORTED:
                self.warn(where, '<%s> %s: %s; skipped' % (
                    child.tag, _quote(child.get('name', '')), _MODEL_UNSUPPORTED[child.tag]))
        if not model.links:
            if elem.find('link') is not None and len(self.warnings) > warnings_before:
                # Its links were skipped with a warning each: say the model went with them.
                self.warnings[-1] += ", and so model %s, which has no usable link left" % (
                    _quote(name))
            else:
                self.warn(where, 'has no links; skipped')
            return None
        return model

    def include(self, elem):
        """An <include>d model: model://ground_plane and model://sun are built in (as Gazebo ships
        them); any other model is read from its folder on the model path (model.config picks the
        SDF file), with the include's <name>, <pose> and <static> overriding the model's own."""
        uri = (elem.findtext('uri') or '').strip()
        target = uri.rstrip('/')
        if target == 'model://sun':
            return None  # a light, not a model: world() reads it with light_of_include
        if target == 'model://ground_plane':
            return self.ground_plane(elem)
        where = 'include %s' % _quote(uri or '(no uri)')
        if not uri:
            self.warn(where, 'no <uri>; give <uri>model://NAME</uri>; skipped')
            return None
        name = (elem.findtext('name') or '').strip()
        if target in self._missing_models:
            self._missing_models[target][1].append(name or target)
            return None
        folder = self.model_folder(target)
        if folder.missing:
            # one warning per missing model however often it is included, given with the world's others
            self._missing_models[target] = [folder.problem, [name or target]]
            return None
        if folder.problem is not None:
            return self.skipped(where, folder.problem)
        try:
            sdf_file = model_path.model_sdf_file(folder.path)
        except model_path.ResolveError as err:
            return self.skipped(where, err)
        try:
            root = ET.parse(sdf_file).getroot()
        except (ET.ParseError, OSError) as err:
            return self.skipped(where, '%s cannot be read as XML: %s' % (sdf_file, err))
        model_elem = root if root.tag == 'model' else root.find('model')
        if model_elem is None:
            return self.skipped(where, '%s has no <model> (only models can be included)' % sdf_file)
        try:
            pose = self.pose(elem, where) if elem.find('pose') is not None else None
            static = _child_bool(elem, 'static', None, 'static')
        except _Unusable as err:
            return self.skipped(where, err)
        if name:
            model_elem.set('name', name)  # before reading, so that its warnings name it
        outer_base, self.base_dir = self.base_dir, folder.path
        try:
            model = self.model(model_elem)
        finally:
            self.base_dir = outer_base
        if model is None:
            return None
        if pose is not None:
            model.pose = pose
        if static is not None:
            model.static = static
        return model

    def model_folder(self, target):
        """The _ModelFolder of an included model: model://NAME on the model path, or a file:// or
        plain path to the folder; when it is not there, the problem names every place searched."""
        if target.startswith('model://'):
            name = target[len('model://'):]  # the whole path, as Gazebo looks it up
            if not name:
                return _ModelFolder(problem='names no model; give <uri>model://NAME</uri>')
            folder, searched = model_path.find_model(name, self.search)
            if folder is None:
                return _ModelFolder(problem="model '%s' not found; searched %s; add the folder holding %s/ to "
                                            'GAZEBO_MODEL_PATH (or put the model in ~/.gazebo/models)'
                                            % (name, ', '.join(searched) or '(an empty model path)',
                                               name.split('/')[0]), missing=True)
            if not os.path.isdir(folder):
                return _ModelFolder(problem='%s is a file, not a model folder; an <include> names the folder '
                                            'that holds model.config' % folder)
            return _ModelFolder(folder)
        path = target[len('file://'):] if target.startswith('file://') else os.path.expanduser(target)
        if '://' in path:
            return _ModelFolder(problem='unknown URI scheme; use model://NAME or file:///path/to/model')
        if not os.path.isabs(path):
            path = os.path.join(self.base_dir or os.getcwd(), path)
        if not os.path.isdir(path):
            return _ModelFolder(problem='no model folder at %s' % path)
        return _ModelFolder(path)

    def ground_plane(self, elem):
        name = (elem.findtext('name') or '').strip() or 'ground_plane'
        where = 'include %s' % _quote(name)
        try:
            pose = self.pose(elem, where)
            static = _child_bool(elem, 'static', True, 'static')
        except _Unusable as err:
            return self.skipped(where, err)
        # Gazebo's ground_plane model: a static 100 m x 100 m plane, mu 100, mu2 50.
        def plane():
            return Shape('plane', size=(100.0, 100.0), normal=(0.0, 0.0, 1.0))
        link = Link('link',
                    collisions=[Collision('collision', ZERO_POSE, plane(), 100.0, 50.0)],
                    visuals=[Visual('visual', ZERO_POSE, plane(), GAZEBO_MATERIALS['Gazebo/Grey'])])
        return Model(name, pose=pose, static=static, links=[link])

    def light(self, elem):
        """A world <light>, or None (one warning) when a value is unusable."""
        name = (elem.get('name') or '').strip()
        where = 'light %s' % _quote(name)
        if not name:
            self.warn('world', '<light> without a name; skipped (give it name="...")')
            return None
        try:
            att = elem.find('attenuation')
            default = Light(name)
            attenuation = default.attenuation if att is None else tuple(
                _child_float(att, tag, value, 'attenuation ' + tag)
                for tag, value in zip(('range', 'constant', 'linear', 'quadratic'), default.attenuation))
            colour = lambda tag, value: _floats(elem.findtext(tag), 4, tag) if elem.find(tag) is not None else value
            return Light(name, (elem.get('type') or 'point').strip(),
                         _child_bool(elem, 'cast_shadows', default.cast_shadows, 'cast_shadows'),
                         self.pose(elem, where), colour('diffuse', default.diffuse),
                         colour('specular', default.specular), attenuation,
                         _floats(elem.findtext('direction'), 3, 'direction') if elem.find('direction') is not None
                         else default.direction)
        except _Unusable as err:
            return self.skipped(where, err)

    def light_of_include(self, elem):
        """The sun of an <include> of model://sun (its <name> and <pose> win), else None."""
        if (elem.findtext('uri') or '').strip().rstrip('/') != 'model://sun':
            return None
        name = (elem.findtext('name') or '').strip() or 'sun'
        try:
            pose = self.pose(elem, 'include %s' % _quote(name)) if elem.find('pose') is not None else None
        except _Unusable as err:
            return self.skipped('include %s' % _quote(name), err)
        return sun_light(name, pose)

    def physics(self, world_elem):
        physics = Physics()
        blocks = world_elem.findall('physics')
        chosen = None
        for block in blocks:
            if (block.get('default') or '').strip().lower() in ('1', 'true'):
                chosen = block
                break
        if chosen is None and blocks:
            chosen = blocks[0]
        if chosen is not None:
            physics.type = (chosen.get('type') or 'ode').strip() or 'ode'
            # real_time_update_rate 0 means "as fast as possible" in Gazebo.
            for tag, allow_zero in (('max_step_size', False), ('real_time_factor', False),
                                    ('real_time_update_rate', True)):
                default = getattr(physics, tag)
                try:
                    value = _child_float(chosen, tag, default, tag)
                except _Unusable as err:
                    self.warn('physics', '%s; using the default %g' % (err, default))
                    continue
                if value < 0.0 or (value == 0.0 and not allow_zero):
                    self.warn('physics', '%s must be %s, got %g; using the default %g'
                              % (tag, '>= 0' if allow_zero else '> 0', value, default))
                    continue
                setattr(physics, tag, value)
        gravity = world_elem.find('gravity')
        if gravity is None and chosen is not None:
            gravity = chosen.find('gravity')  # SDF <= 1.5 kept it in <physics>
        if gravity is not None:
            try:
                physics.gravity = _floats(gravity.text, 3, 'gravity')
            except _Unusable as err:
                self.warn('world', '%s; using the default %s' % (err, physics.gravity))
        return physics

    def state(self, state_elem, models):
        """Apply the model and link poses of a saved <state> (world frame), as Gazebo does."""
        by_name = {m.name: m for m in models}
        for tag in ('insertions', 'deletions'):
            if state_elem.find(tag) is not None:
                self.warn('state', '<%s> is not supported; ignored' % tag)
        for model_state in state_elem.findall('model'):
            model = by_name.get(model_state.get('name'))
            if model is None:
                continue
            where = 'state of model %s' % _quote(model.name)
            try:
                scale = model_state.find('scale')
                if scale is not None and _floats(scale.text, 3, 'scale') != (1.0, 1.0, 1.0):
                    self.warn(where, 'model scale is not supported; ignored')
                if model_state.find('pose') is not None:
                    model_pose = self.pose(model_state, where)
                else:
                    model_pose = model.pose
                link_poses = {}
                for link_state in model_state.findall('link'):
                    if link_state.find('pose') is not None:
                        link_poses[link_state.get('name')] = self.pose(
                            link_state, '%s link %s' % (where, _quote(link_state.get('name'))))
            except _Unusable as err:
                self.warn(where, '%s; the state is ignored for this model' % err)
                continue
            model.pose = model_pose
            to_model = inverse(model_pose)
            for link in model.links:
                if link.name in link_poses:
                    link.pose = as_xyz_rpy(compose(to_model, link_poses[link.name]))

    # -- the world --------------------------------------------------------------------

    def world(self, root):
        if root.tag == 'world':
            world_elem = root
        else:
            worlds = root.findall('world')
            if not worlds:
                has_model = root.find('model') is not None
                raise WorldError(
                    '%s has no <world> element (root is <%s>); a world file looks like '
                    '<sdf version="1.6"><world name="default">...</world></sdf>%s'
                    % (self.source, root.tag,
                       '; this looks like a model file: spawn it with spawn_model -sdf -file'
                       if has_model else ''))
            if len(worlds) > 1:
                self.warn('', '%d <world> elements; only the first (%s) is loaded'
                          % (len(worlds), _quote(worlds[0].get('name', 'default'))))
            world_elem = worlds[0]
        world = World(name=world_elem.get('name') or 'default', source=self.source)
        world.physics = self.physics(world_elem)
        names = set()
        for child in world_elem:
            model = None
            if child.tag == 'model':
                model = self.model(child)
            elif child.tag == 'include':
                model = self.include(child)
                light = self.light_of_include(child)
                if light is not None:
                    world.lights.append(light)
            elif child.tag == 'light':
                light = self.light(child)
                if light is not None:
                    world.lights.append(light)
            elif child.tag in _WORLD_UNSUPPORTED:
                self.warn('world', '<%s> %s: %s; skipped' % (
                    child.tag, _quote(child.get('name', '')), _WORLD_UNSUPPORTED[child.tag]))
            elif child.tag not in _WORLD_SILENT:
                self.warn('world', 'unknown element <%s>; ignored' % child.tag)
            if model is None:
                continue
            if model.name in names:
                self.warn('model %s' % _quote(model.name),
                          'a second model with this name; skipped (names must be unique)')
                continue
            names.add(model.name)
            world.models.append(model)
        state = world_elem.find('state')
        if state is not None:
            self.state(state, world.models)
        for uri, (message, names) in self._missing_models.items():
            self.warn('include %s' % _quote(uri), '%s; skipped%s' % (message, '' if len(names) == 1 else (
                ' (all %d includes of it: %s)' % (len(names), ', '.join(names)))))
        world.warnings = self.warnings
        return world


def parse_world(xml_text, source='<string>', search=None):
    """Parse SDF world text (str or bytes, or its root element already parsed) into a World.  ``source``
    names it in messages (and, when it is a file, relative mesh URIs are relative to its folder);
    ``search``: the model path for model:// URIs (default: model_path.model_path())."""
    if isinstance(xml_text, ET.Element):
        return _WorldReader(source, search).world(xml_text)
    try:
        root = ET.fromstring(xml_text)
    except ET.ParseError as err:
        # The parser's message ends with "line L, column C" (column counted from 0).
        raise WorldError('%s is not valid XML: %s; check it with xmllint or `gz sdf -k`'
                         % (source, err)) from None
    except (ValueError, LookupError, TypeError) as err:
        raise WorldError('%s could not be read as XML: %s' % (source, err)) from None
    return _WorldReader(source, search).world(root)


def load_world(path, search_path=()):
    """Read the world file at ``path``.

    A relative path that does not exist is looked for under each directory of
    ``search_path`` (as Gazebo searches GAZEBO_RESOURCE_PATH); ``worlds/empty.world`` not
    found anywhere is Gazebo's empty world (ground plane and sun), built in.
    """
    path = os.path.expanduser(str(path))
    candidates = [path]
    if not os.path.isabs(path):
        candidates += [os.path.join(d, path) for d in search_path if d]
    found = next((c for c in candidates if os.path.exists(c)), None)
    if found is None:
        if os.path.normpath(path) in _EMPTY_WORLD_NAMES:
            return parse_world(EMPTY_WORLD_SDF, source='%s (built in)' % path)
        raise WorldError(
            "world file '%s' not found%s; pass an existing file, e.g. "
            "world_name:=$(find racebot_gazebo)/worlds/room_mini.world"
            % (path, ' (also looked under %s)' % ', '.join(search_path) if search_path else ''))
    if os.path.isdir(found):
        raise WorldError("world file '%s' is a directory; pass the .world file inside it, e.g. "
                         "world_name:=$(find racebot_gazebo)/worlds/room_mini.world" % found)
    try:
        with open(found, 'rb') as handle:
            data = handle.read()
    except OSError as err:
        raise WorldError("world file '%s' cannot be read: %s" % (found, err.strerror)) from None
    return parse_world(data, source=found)

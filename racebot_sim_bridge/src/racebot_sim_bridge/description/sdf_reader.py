"""Read SDF 1.6 world files into sdf_model's dataclasses: ``load_world``, ``parse_world``.

Pure Python: no rospy, no pybullet.  ``physics.py`` turns the result into bodies. The values of each
element (numbers, poses, shapes, meshes, colours) are read by sdf_elements.ElementReader, which the world
reader here extends with the world's structure. Files are read as TinyXML reads them (xml_document: a blank
line before ``<?xml ...?>`` is no error).

What is understood: the world's physics block and gravity; models made of links with box,
cylinder, sphere, plane and mesh geometry, their poses, masses, inertias, ODE friction (mu, mu2)
and visual colours (explicit or Gazebo material script names); ``<include>`` of models from the
Gazebo model path (model_path.py: ~/.gazebo/models, GAZEBO_MODEL_PATH, packages' gazebo_model_path
exports; model.config picks the SDF file) with the include's name, pose, static and plugins,
``model://ground_plane`` and ``model://sun`` built in as Gazebo ships them; the first ``<state>``
block's model and link poses, which Gazebo applies when it loads a saved world.  Mesh URIs
(model://, package://, file://, paths) are resolved and the files converted while reading
(sdf_elements, meshes.convert), so a parsed world names only absolute files and needs no search path again.

Nested models are one Model, as Gazebo 11 has them for gazebo_ros (the outer model is the model; its nested
links are outer::inner::link): an ``<include>`` inside a ``<model>`` is flattened into it as sdformat 9's
parser does (its links, joints and nested models renamed NAME::old, references to them in joints and plugins
too, posed at the include's pose); a ``<model>`` inside a ``<model>`` is read into it as Gazebo loads it (its
links and joints named inner::old, posed through every level, static by its own ``<static>``), after the outer
model's own links, so the first link is Gazebo's canonical one.

A model's joints (revolute, prismatic, fixed), its ``<plugin>``s and its links' ``<sensor>``s are
kept (plugins and sensors as the XML written): such a model is a robot, spawned through the URDF
path (sdf_urdf.py).  Everything else that matters to the physics (heightmap and polyline
geometry, world plugins, actors) is skipped with ONE entry in
``World.warnings`` naming the element, where it is and why; so are elements whose values are
unusable (non-numeric, non-finite, zero or negative sizes) and models or meshes that cannot be
found (the warning names the URI and every place searched) or read.  Only a missing file, text
that is not XML and a document without ``<world>`` raise ``WorldError``.
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from typing import NamedTuple

from racebot_sim_bridge.description import model_path, xml_document
from racebot_sim_bridge.description.geometry import Shape
from racebot_sim_bridge.description.materials import GAZEBO_MATERIALS
from racebot_sim_bridge.description.sdf_elements import Unusable, child_bool, child_float, floats, quote
from racebot_sim_bridge.description.sdf_includes import BASE_DIR, IncludeReader
from racebot_sim_bridge.description.sdf_model import (UNLIMITED, ZERO_POSE, Collision, Joint, Light, Link, Model,
                                                      Physics, Visual, World)
from racebot_sim_bridge.kinematics.rotations import XyzRpy, as_transform, as_xyz_rpy, compose, inverse, rotate

__all__ = ['WorldError', 'parse_world', 'load_world', 'sun_light', 'EMPTY_WORLD_SDF']

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


def sun_light(name: str = 'sun', pose: XyzRpy | None = None) -> Light:
    """Gazebo's model://sun: one directional light (its model.sdf's values)."""
    return Light(name, 'directional', True, pose or (0.0, 0.0, 10.0, 0.0, 0.0, 0.0), (0.8, 0.8, 0.8, 1.0),
                 (0.2, 0.2, 0.2, 1.0), (1000.0, 0.9, 0.01, 0.001), (-0.5, 0.1, -0.9))


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


def _keep(items, item):
    """Appends `item` unless it is None (skipped, and warned about where it was read)."""
    if item is not None:
        items.append(item)


class _Scope(NamedTuple):
    """A level of a model as its links are read: the outer model itself, or a nested <model> in it. `prefix`: the
    nested models' names down to it, each followed by '::' ('' for the outer model); `pose`: its frame in the outer
    model's; `static`: a nested model's own <static> (None: the outer model's); `where`: for messages;
    `base_dir`: what relative mesh URIs in it are relative to; `around`: the prefixes of the models around it,
    outermost first."""
    prefix: str = ''
    pose: tuple = ZERO_POSE
    static: bool = None
    where: str = ''
    base_dir: str = None
    around: tuple = ()


class _WorldReader(IncludeReader):
    def unsupported(self, where, child, reasons):
        """Warns that `child` is skipped for its tag's reason in `reasons`."""
        self.warn(where, '<%s> %s: %s; skipped' % (child.tag, quote(child.get('name', '')), reasons[child.tag]))

    # -- elements ---------------------------------------------------------------------

    def placed_shape(self, elem, where):
        """(name, where, pose, _Geometry) of a <collision> or <visual>, or None when it is skipped (warned)."""
        name = elem.get('name', '')
        where = '%s %s %s' % (where, elem.tag, quote(name))
        try:
            pose = self.pose(elem, where)
        except Unusable as err:
            return self.skipped(where, err)
        geometry = self.shape(elem.find('geometry'), where)
        if geometry is None:
            return None
        return name, where, pose, geometry

    def collision(self, elem, where):
        placed = self.placed_shape(elem, where)
        if placed is None:
            return None
        name, where, pose, geometry = placed
        mu = mu2 = None
        ode = elem.find('surface/friction/ode')
        if ode is not None:
            try:
                mu = child_float(ode, 'mu', None, 'friction mu')
                mu2 = child_float(ode, 'mu2', None, 'friction mu2')
            except Unusable as err:
                return self.skipped(where, err)
            for label, value in (('mu', mu), ('mu2', mu2)):
                if value is not None and value < 0.0:
                    return self.skipped(where, 'friction %s must be >= 0, got %g' % (label, value))
        try:
            retro = child_float(elem, 'laser_retro', 0.0, 'laser_retro')
        except Unusable as err:
            return self.skipped(where, err)
        return Collision(name, pose, geometry.shape, mu, mu2, retro)

    def visual(self, elem, where):
        placed = self.placed_shape(elem, where)
        if placed is None:
            return None
        name, where, pose, geometry = placed
        try:
            # an SDF <material> overrides the mesh's own, as in Gazebo
            rgba = self.rgba(elem.find('material')) or geometry.mesh_rgba
        except Unusable as err:
            return self.skipped(where, err)
        return Visual(name, pose, geometry.shape, rgba)

    def link(self, elem, where, static=False):
        name = elem.get('name')
        if not name:
            self.warn(where, 'a <link> without a name; skipped')
            return None
        where = '%s link %s' % (where, quote(name))
        try:
            link = Link(name, pose=self.pose(elem, where))
            inertial = elem.find('inertial')
            if inertial is not None:
                mass = child_float(inertial, 'mass', 1.0, 'mass')
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
                    link.inertia = tuple(child_float(inertia, key, default, key)
                                         for key, default in defaults.items())
        except Unusable as err:
            return self.skipped(where, err)
        for child in elem:
            if child.tag == 'collision':
                _keep(link.collisions, self.collision(child, where))
            elif child.tag == 'visual':
                _keep(link.visuals, self.visual(child, where))
            elif child.tag == 'sensor':
                link.sensors.append(ET.tostring(child, encoding='unicode'))
            elif child.tag in _LINK_UNSUPPORTED:
                self.unsupported(where, child, _LINK_UNSUPPORTED)
        return link

    def joint(self, elem, where):
        """A <joint>; None (warned) when unusable.  ball, universal, revolute2, screw and gearbox
        joints are not simulated: made fixed, with a warning, so that the links stay joined."""
        name = elem.get('name')
        if not name:
            return self.skipped(where, 'a <joint> without a name')
        where = '%s joint %s' % (where, quote(name))
        kind = elem.get('type', '')
        parent, child = (elem.findtext('parent') or '').strip(), (elem.findtext('child') or '').strip()
        if not parent or not child:
            return self.skipped(where, 'a joint needs <parent> and <child> link names')
        if kind not in ('revolute', 'prismatic', 'fixed'):
            if kind not in ('ball', 'universal', 'revolute2', 'screw', 'gearbox'):
                return self.skipped(where, 'unknown joint type %s (SDF has revolute, prismatic, fixed, ball, '
                                    'universal, revolute2, screw, gearbox)' % quote(kind))
            self.warn(where, '%s joints are not supported; made fixed' % kind)
            kind = 'fixed'
        try:
            joint = Joint(name, kind, parent, child, pose=self.pose(elem, where))
            axis = elem.find('axis')
            if axis is not None and kind != 'fixed':
                xyz = axis.find('xyz')
                if xyz is not None:
                    joint.axis = floats(xyz.text, 3, 'axis xyz')
                    joint.axis_in_model = xyz.get('expressed_in') == '__model__'
                joint.axis_in_model = child_bool(axis, 'use_parent_model_frame', joint.axis_in_model,
                                                 'use_parent_model_frame')
                if not any(joint.axis):
                    raise Unusable('axis xyz is the zero vector; give the direction the joint moves along')
                limit = axis.find('limit')
                if limit is not None:
                    joint.lower = child_float(limit, 'lower', -UNLIMITED, 'limit lower')
                    joint.upper = child_float(limit, 'upper', UNLIMITED, 'limit upper')
                    joint.effort = child_float(limit, 'effort', -1.0, 'limit effort')
                    joint.velocity = child_float(limit, 'velocity', -1.0, 'limit velocity')
                    if joint.lower > joint.upper:
                        raise Unusable('limit lower %g is above upper %g' % (joint.lower, joint.upper))
                dynamics = axis.find('dynamics')
                if dynamics is not None:
                    joint.damping = child_float(dynamics, 'damping', 0.0, 'dynamics damping')
                    joint.friction = child_float(dynamics, 'friction', 0.0, 'dynamics friction')
                    if joint.damping < 0 or joint.friction < 0:
                        raise Unusable('dynamics damping and friction must be >= 0, got %g and %g'
                                       % (joint.damping, joint.friction))
        except Unusable as err:
            return self.skipped(where, err)
        return joint

    def model(self, elem):
        """A <model> of the world (or the model of a world-level <include>), as one Model: the <include>s in it
        flattened into it as sdformat's parser does (expand_includes), its nested <model>s read into it as
        Gazebo loads them (read_level): their links named inner::link, posed in the outer model's frame."""
        name = elem.get('name')
        if not name:
            self.warn('world', 'a <model> without a name; skipped')
            return None
        where = 'model %s' % quote(name)
        self.expand_includes(elem, where)
        try:
            # the first <static> in the model after the includes are flattened: sdformat keeps every one and
            # Gazebo reads the first (an included model's own comes where its <include> stood)
            model = Model(name, pose=self.pose(elem, where),
                          static=child_bool(elem, 'static', False, 'static'))
        except Unusable as err:
            return self.skipped(where, err)
        warnings_before = len(self.warnings)
        joints = []
        self.read_level(model, elem, _Scope(where=where, base_dir=self.base_dir), joints)
        names = {link.name for link in model.links}
        for joint, scope in joints:
            joint.parent, joint.child = (self.scoped_link(model, names, joint.parent, scope),
                                         self.scoped_link(model, names, joint.child, scope))
            model.joints.append(joint)
        if not model.links:
            if any(elem.iter('link')) and len(self.warnings) > warnings_before:
                # Its links were skipped with a warning each: say the model went with them.
                self.warnings[-1] += ", and so model %s, which has no usable link left" % (
                    quote(name))
            else:
                self.warn(where, 'has no links; skipped')
            return None
        return model

    def read_level(self, model, elem, scope, joints):
        """Reads the links, joints and plugins of `elem` (the outer <model> or a nested one, as `scope` says) into
        `model`, then its nested <model>s, depth first: Gazebo's order (Model::LoadLinks, then LoadModels), so the
        first link of the list is Gazebo's canonical link. Joints go to `joints` with their scope, their links
        found once all are read."""
        nested = []
        for child in elem:
            if child.tag == 'link':
                base_dir = child.get(BASE_DIR) or scope.base_dir
                with self.relative_to(base_dir):
                    link = self.link(child, scope.where, model.static if scope.static is None else scope.static)
                if link is None:
                    continue
                if scope.prefix:
                    link.name = scope.prefix + link.name
                    link.pose = as_xyz_rpy(compose(scope.pose, link.pose))
                    link.static = scope.static
                if any(other.name == link.name for other in model.links):
                    self.warn(scope.where, 'a second link %s; skipped' % quote(link.name))
                    continue
                model.links.append(link)
            elif child.tag == 'joint':
                joint = self.joint(child, scope.where)
                if joint is not None:
                    joint.name = scope.prefix + joint.name
                    if joint.axis_in_model and scope.prefix:  # the nested model's frame, turned into the outer's
                        joint.axis = rotate(as_transform(scope.pose)[1], joint.axis)
                    joints.append((joint, scope))
            elif child.tag == 'plugin':
                if scope.prefix:
                    self.warn(scope.where, '<plugin> %s runs with model %s: a nested model is part of its outer '
                              'model here, its links and joints named %sNAME' % (
                                  quote(child.get('name', '')), quote(model.name), scope.prefix))
                model.plugins.append(ET.tostring(child, encoding='unicode'))
            elif child.tag == 'model':
                nested.append(child)
            elif child.tag in _MODEL_UNSUPPORTED:
                self.unsupported(scope.where, child, _MODEL_UNSUPPORTED)
        for child in nested:
            name = child.get('name')
            if not name:
                self.warn(scope.where, 'a nested <model> without a name; skipped')
                continue
            where = '%s model %s' % (scope.where, quote(name))
            try:
                pose = self.pose(child, where)
                # Gazebo: a nested model is static by its own <static> (Model::Load), not by its outer model's
                static = child_bool(child, 'static', False, 'static')
            except Unusable as err:
                self.skipped(where, err)
                continue
            self.read_level(model, child, _Scope(scope.prefix + name + '::', as_xyz_rpy(compose(scope.pose, pose)),
                                                 static, where, child.get(BASE_DIR) or scope.base_dir,
                                                 scope.around + (scope.prefix,)), joints)

    @staticmethod
    def scoped_link(model, names, name, scope):
        """The link of `model` (flattened, names in `names`) a joint of `scope` names, as Gazebo's Joint::Load
        finds it: in the joint's own (nested) model, then in each model around it; `world` is the world. A name
        found nowhere is kept (scoped), for sdf_urdf to say which link is missing."""
        if name == 'world':
            return name
        for prefix in (scope.prefix,) + scope.around[::-1]:
            if prefix + name in names:
                return prefix + name
        if name.startswith(model.name + '::') and name[len(model.name) + 2:] in names:
            return name[len(model.name) + 2:]  # the link's scoped name, world-wide
        return scope.prefix + name

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
        where = 'include %s' % quote(uri or '(no uri)')
        if not uri:
            self.warn(where, 'no <uri>; give <uri>model://NAME</uri>; skipped')
            return None
        name = (elem.findtext('name') or '').strip()
        if target in self.missing_models:
            self.missing_models[target][1].append(name or target)
            return None
        folder = self.model_folder(target)
        if folder.missing:
            # one warning per missing model however often it is included, given with the world's others
            self.missing_models[target] = [folder.problem, [name or target]]
            return None
        if folder.problem is not None:
            return self.skipped(where, folder.problem)
        model_elem = self.model_element(folder.path, where)
        if model_elem is None:
            return None
        try:
            pose = self.pose(elem, where) if elem.find('pose') is not None else None
            static = child_bool(elem, 'static', None, 'static')
        except Unusable as err:
            return self.skipped(where, err)
        if name:
            model_elem.set('name', name)  # before reading, so that its warnings name it
        model_elem.extend(elem.findall('plugin'))  # sdformat adds the include's plugins to the model
        with self.relative_to(folder.path):
            model = self.model(model_elem)
        if model is None:
            return None
        if pose is not None:
            model.pose = pose
        if static is not None:
            model.static = static
        return model

    def ground_plane(self, elem):
        name = (elem.findtext('name') or '').strip() or 'ground_plane'
        where = 'include %s' % quote(name)
        try:
            pose = self.pose(elem, where)
            static = child_bool(elem, 'static', True, 'static')
        except Unusable as err:
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
        where = 'light %s' % quote(name)
        if not name:
            self.warn('world', '<light> without a name; skipped (give it name="...")')
            return None
        try:
            att = elem.find('attenuation')
            default = Light(name)
            attenuation = default.attenuation if att is None else tuple(
                child_float(att, tag, value, 'attenuation ' + tag)
                for tag, value in zip(('range', 'constant', 'linear', 'quadratic'), default.attenuation))
            colour = lambda tag, value: floats(elem.findtext(tag), 4, tag) if elem.find(tag) is not None else value
            return Light(name, (elem.get('type') or 'point').strip(),
                         child_bool(elem, 'cast_shadows', default.cast_shadows, 'cast_shadows'),
                         self.pose(elem, where), colour('diffuse', default.diffuse),
                         colour('specular', default.specular), attenuation,
                         floats(elem.findtext('direction'), 3, 'direction') if elem.find('direction') is not None
                         else default.direction)
        except Unusable as err:
            return self.skipped(where, err)

    def light_of_include(self, elem):
        """The sun of an <include> of model://sun (its <name> and <pose> win), else None."""
        if (elem.findtext('uri') or '').strip().rstrip('/') != 'model://sun':
            return None
        name = (elem.findtext('name') or '').strip() or 'sun'
        try:
            pose = self.pose(elem, 'include %s' % quote(name)) if elem.find('pose') is not None else None
        except Unusable as err:
            return self.skipped('include %s' % quote(name), err)
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
                    value = child_float(chosen, tag, default, tag)
                except Unusable as err:
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
                physics.gravity = floats(gravity.text, 3, 'gravity')
            except Unusable as err:
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
            where = 'state of model %s' % quote(model.name)
            try:
                scale = model_state.find('scale')
                if scale is not None and floats(scale.text, 3, 'scale') != (1.0, 1.0, 1.0):
                    self.warn(where, 'model scale is not supported; ignored')
                if model_state.find('pose') is not None:
                    model_pose = self.pose(model_state, where)
                else:
                    model_pose = model.pose
                link_poses = {}
                levels = [('', model_state)]  # a nested model's links are inner::link (world poses, as the rest)
                for prefix, level in levels:
                    levels.extend((prefix + nested.get('name', '') + '::', nested) for nested in level.findall('model'))
                    for link_state in level.findall('link'):
                        if link_state.find('pose') is not None:
                            name = prefix + link_state.get('name', '')
                            link_poses[name] = self.pose(link_state, '%s link %s' % (where, quote(name)))
            except Unusable as err:
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
                          % (len(worlds), quote(worlds[0].get('name', 'default'))))
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
                _keep(world.lights, self.light_of_include(child))
            elif child.tag == 'light':
                _keep(world.lights, self.light(child))
            elif child.tag in _WORLD_UNSUPPORTED:
                self.unsupported('world', child, _WORLD_UNSUPPORTED)
            elif child.tag not in _WORLD_SILENT:
                self.warn('world', 'unknown element <%s>; ignored' % child.tag)
            if model is None:
                continue
            if model.name in names:
                self.warn('model %s' % quote(model.name),
                          'a second model with this name; skipped (names must be unique)')
                continue
            names.add(model.name)
            world.models.append(model)
        state = world_elem.find('state')
        if state is not None:
            self.state(state, world.models)
        for uri, (message, names) in self.missing_models.items():
            self.warn('include %s' % quote(uri), '%s; skipped%s' % (message, '' if len(names) == 1 else (
                ' (all %d includes of it: %s)' % (len(names), ', '.join(names)))))
        world.warnings = self.warnings
        return world


def parse_world(xml_text: str | bytes | ET.Element, source: str = '<string>',
                search: list[str] | None = None) -> World:
    """Parse SDF world text (str or bytes, or its root element already parsed) into a World.  ``source`` names it
    in messages (and, when it is a file, relative mesh URIs are relative to its folder); ``search``: the model
    path for model:// URIs (default: model_path.model_path())."""
    if isinstance(xml_text, ET.Element):
        return _WorldReader(source, search).world(xml_text)
    try:
        root = xml_document.fromstring(xml_text)  # as TinyXML: a blank line before <?xml ...?> is no error
    except ET.ParseError as err:
        # The parser's message ends with "line L, column C" (column counted from 0).
        raise WorldError('%s is not valid XML: %s; check it with xmllint or `gz sdf -k`'
                         % (source, err)) from None
    except (ValueError, LookupError, TypeError) as err:
        raise WorldError('%s could not be read as XML: %s' % (source, err)) from None
    return _WorldReader(source, search).world(root)


def load_world(path: str | os.PathLike, search_path: Sequence[str] = ()) -> World:
    """Read the world file at ``path``.

    A relative path that does not exist is looked for under each directory of ``search_path`` (the resource
    path: as SystemPaths::FindFile, also under its models/, media/models/ and Media/models/); ``worlds/empty.world``
    not found anywhere is Gazebo's empty world (ground plane and sun), built in.
    """
    path = os.path.expanduser(str(path))
    candidates = [path]
    if not os.path.isabs(path):
        candidates += [os.path.join(d, suffix, path) for d in search_path if d
                       for suffix in model_path.RESOURCE_SUFFIXES]
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

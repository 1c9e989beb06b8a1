"""Read SDF 1.6 world files into sdf_model's dataclasses: ``load_world``, ``parse_world``.

Pure Python: no rospy, no pybullet.  ``physics.py`` turns the result into bodies. The values of each
element (numbers, poses, shapes, meshes, colours) are read by sdf_elements.ElementReader, links and joints by
sdf_links, models (their includes and nested models) by sdf_models, which the world reader here extends with the
world's physics, lights and saved state. Files are read as TinyXML reads them (xml_document: a blank
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
path (sdf_urdf.py). A world's ``<plugin>``s are kept as written (``World.plugins``; the world server loads them
as compiled world plugins after the models). Everything else that matters to the physics (heightmap and polyline
geometry, actors) is skipped with ONE entry in
``World.warnings`` naming the element, where it is and why; so are elements whose values are
unusable (non-numeric, non-finite, zero or negative sizes) and models or meshes that cannot be
found (the warning names the URI and every place searched) or read.  Only a missing file, text
that is not XML and a document without ``<world>`` raise ``WorldError``.
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Sequence

from racebot_sim_bridge.description import model_path, xml_document
from racebot_sim_bridge.description.sdf_elements import Unusable, child_bool, child_float, floats, quote
from racebot_sim_bridge.description.sdf_links import keep
from racebot_sim_bridge.description.sdf_model import FRICTION_MODELS, ODE_SETTINGS, Light, Physics, World, WorldPlugin
from racebot_sim_bridge.description.sdf_models import ModelReader
from racebot_sim_bridge.kinematics.rotations import XyzRpy, as_xyz_rpy, compose, inverse

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
    'road': 'roads are not supported',
    'population': 'populations are not supported; write the models out',
    'frame': 'frames are not supported',
}


class _WorldReader(ModelReader):
    """Reads a world: its physics, models, lights and saved state (see the module)."""

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
            for name, path, default, integer, least in ODE_SETTINGS:
                try:
                    value = child_float(chosen, path, default, path.rsplit('/', 1)[-1])
                except Unusable as err:
                    self.warn('physics', '%s; using the default %g' % (err, default))
                    continue
                if value < least or (integer and value != int(value)):
                    self.warn('physics', '%s must be a %s >= %d, got %g; using the default %g'
                              % (path, 'whole number' if integer else 'number', least, value, default))
                    continue
                physics.ode[name] = int(value) if integer else value
            model = (chosen.findtext('ode/solver/friction_model') or '').strip()
            if model in FRICTION_MODELS:
                physics.friction_model = model
            elif model:
                self.warn('physics', 'friction_model %s is not simulated (racebot has %s); using the default %s'
                          % (quote(model), ' and '.join(FRICTION_MODELS), physics.friction_model))
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

    def world_plugin(self, elem):
        """A world <plugin>, or None (one warning) without a filename."""
        name, filename = (elem.get('name') or '').strip(), (elem.get('filename') or '').strip()
        if not filename:
            self.warn('world', '<plugin> %s has no filename; skipped (give filename="libname.so")' % quote(name))
            return None
        return WorldPlugin(name, filename, ET.tostring(elem, encoding='unicode'))

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
                keep(world.lights, self.light_of_include(child))
            elif child.tag == 'light':
                keep(world.lights, self.light(child))
            elif child.tag == 'plugin':
                keep(world.plugins, self.world_plugin(child))
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

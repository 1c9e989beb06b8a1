"""An SDF model's links and joints read with warnings: collisions, visuals, inertials, sensors, joint axes.

Pure Python: no rospy, no pybullet. LinkReader is the part of sdf_reader's world reader that reads one <link>
(its <collision>s with their ODE friction and laser_retro, its <visual>s with their colour, its inertial, its
<sensor>s as written) and one <joint> (type, links, axis, limits, dynamics); sdf_models puts them together into
a model. What cannot be used is skipped with one warning, as ElementReader's values are.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from racebot_sim_bridge.description.sdf_elements import ElementReader, Unusable, child_bool, child_float, floats, quote
from racebot_sim_bridge.description.sdf_model import UNLIMITED, Collision, SdfJoint, SdfLink, Visual

__all__ = ['LinkReader', 'keep']

_LINK_UNSUPPORTED = {
    'projector': 'projectors are not supported',
    'light': 'lights are not simulated',
    'audio_source': 'audio is not supported',
    'audio_sink': 'audio is not supported',
    'battery': 'batteries are not supported',
    'particle_emitter': 'particle emitters are not supported',
}


def keep(items: list, item: object | None) -> None:
    """Appends `item` unless it is None (skipped, and warned about where it was read)."""
    if item is not None:
        items.append(item)


class LinkReader(ElementReader):
    """Reads <link>s and <joint>s (see the module), warning into ``warnings`` as ElementReader does."""

    def placed_shape(self, elem: ET.Element, where: str) -> tuple | None:
        """(name, where, pose, sdf_elements' _Geometry) of a <collision> or <visual>, or None when it is skipped
        (warned)."""
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

    def collision(self, elem: ET.Element, where: str) -> Collision | None:
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

    def visual(self, elem: ET.Element, where: str) -> Visual | None:
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

    def link(self, elem: ET.Element, where: str, static: bool = False) -> SdfLink | None:
        name = elem.get('name')
        if not name:
            self.warn(where, 'a <link> without a name; skipped')
            return None
        where = '%s link %s' % (where, quote(name))
        try:
            link = SdfLink(name, pose=self.pose(elem, where))
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
                keep(link.collisions, self.collision(child, where))
            elif child.tag == 'visual':
                keep(link.visuals, self.visual(child, where))
            elif child.tag == 'sensor':
                link.sensors.append(ET.tostring(child, encoding='unicode'))
            elif child.tag in _LINK_UNSUPPORTED:
                self.unsupported(where, child, _LINK_UNSUPPORTED)
        return link

    def joint(self, elem: ET.Element, where: str) -> SdfJoint | None:
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
            joint = SdfJoint(name, kind, parent, child, pose=self.pose(elem, where))
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

"""An SDF <model> read as Gazebo 11 loads it for gazebo_ros: one Model, its nested models and includes in it.

Pure Python: no rospy, no pybullet. ModelReader is the part of sdf_reader's world reader that reads a world's
<model> or the model of a world-level <include>: the <include>s inside it flattened as sdformat 9's parser does
(sdf_includes), its links and joints (sdf_links) and those of its nested <model>s read into it (named
inner::link, posed through every level, static by their own <static>), after the outer model's own links, so the
first link is Gazebo's canonical one; joints find their links as Gazebo's Joint::Load does. model://ground_plane
is built in, as Gazebo ships it.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import NamedTuple

from racebot_sim_bridge.description.geometry import Shape
from racebot_sim_bridge.description.materials import GAZEBO_MATERIALS
from racebot_sim_bridge.description.sdf_elements import Unusable, child_bool, quote
from racebot_sim_bridge.description.sdf_includes import BASE_DIR, IncludeReader
from racebot_sim_bridge.description.sdf_links import LinkReader
from racebot_sim_bridge.description.sdf_model import ZERO_POSE, Collision, SdfJoint, SdfLink, SdfModel, Visual
from racebot_sim_bridge.kinematics.rotations import as_transform, as_xyz_rpy, compose, rotate

__all__ = ['ModelReader']

_MODEL_UNSUPPORTED = {
    'gripper': 'grippers are not supported',
}


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


class ModelReader(IncludeReader, LinkReader):
    """Reads models (see the module), warning into ``warnings`` as ElementReader does."""

    def model(self, elem: ET.Element) -> SdfModel | None:
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
            model = SdfModel(name, pose=self.pose(elem, where),
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

    def read_level(self, model: SdfModel, elem: ET.Element, scope: _Scope,
                   joints: list[tuple[SdfJoint, _Scope]]) -> None:
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
    def scoped_link(model: SdfModel, names: set[str], name: str, scope: _Scope) -> str:
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

    def include(self, elem: ET.Element) -> SdfModel | None:
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
        found = self.included_model(target, name, where)
        if found is None:
            return None
        folder, model_elem = found
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

    def ground_plane(self, elem: ET.Element) -> SdfModel | None:
        """Gazebo's model://ground_plane, built in, with the include's <name>, <pose> and <static>."""
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
        link = SdfLink('link',
                    collisions=[Collision('collision', ZERO_POSE, plane(), 100.0, 50.0)],
                    visuals=[Visual('visual', ZERO_POSE, plane(), GAZEBO_MATERIALS['Gazebo/Grey'])])
        return SdfModel(name, pose=pose, static=static, links=[link])

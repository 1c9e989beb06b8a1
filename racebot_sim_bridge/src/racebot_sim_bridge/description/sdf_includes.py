"""Included models as sdformat 9 reads them: where an <include> finds its model, and an <include> inside a <model>.

Pure Python: no rospy, no pybullet. IncludeReader is the part of sdf_reader's world reader that reads the models
an <include> names: model://NAME on the model path (model_path.find_model), a file:// URI or a path (as
SystemPaths::FindFile finds it), model.config picking the SDF file. An <include> inside a <model> is flattened into
it as sdformat 9's parser does (parser.cc readXml, addNestedModel): Gazebo 11 sees its links, joints and nested
models as the outer model's own, renamed NAME::old; the world reader (sdf_reader) then reads the model.
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from contextlib import contextmanager
from typing import Iterator, NamedTuple

from racebot_sim_bridge.description import model_path, xml_document
from racebot_sim_bridge.description.sdf_elements import ElementReader, Unusable, child_bool, floats, quote
from racebot_sim_bridge.description.sdf_model import ZERO_POSE
from racebot_sim_bridge.kinematics.rotations import as_transform, as_xyz_rpy, compose, rotate

__all__ = ['IncludeReader', 'BASE_DIR']


class _ModelFolder(NamedTuple):
    """Where an <include>d model is: `path`, or None and `problem` (what is wrong, what to do).
    `missing`: the model is on no folder of the model path; such includes are warned about once per
    URI, all together, after the world is read."""
    path: str = None
    problem: str = None
    missing: bool = False


# Where an element flattened out of an included model came from: its model folder, which relative mesh URIs are
# relative to (an attribute of the flattened <link> or <model>; the reader's own, never written out).
BASE_DIR = '{urn:racebot}base_dir'

# Gazebo's model://ground_plane (its model.sdf), for an <include> of it inside a <model>.
_GROUND_PLANE_SDF = """<model name="ground_plane"><static>true</static><link name="link">
<collision name="collision"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
<surface><friction><ode><mu>100</mu><mu2>50</mu2></ode></friction></surface></collision>
<visual name="visual"><cast_shadows>false</cast_shadows><geometry><plane><normal>0 0 1</normal><size>100 100</size>
</plane></geometry><material><script><name>Gazebo/Grey</name></script></material></visual></link></model>"""


def _scoped_text(text, replace):
    """sdformat 9's renaming of a model included inside a model (parser.cc addNestedModel): every name in
    `replace` (old -> new, in the order of its keys) written as "old", 'old', >old< or >old:: in `text` becomes
    the new one; so joints' <parent>/<child> and plugins' values that name a link or joint follow it."""
    for old in sorted(replace):
        new = replace[old]
        for form in ('"%s"', "'%s'", '>%s<', '>%s::'):
            text = text.replace(form % old, form % new)
    return text


class IncludeReader(ElementReader):
    """Reads what <include>s name (see the module), warning into ``warnings`` as ElementReader does. A model:// that
    is on no folder of the model path is collected in ``missing_models`` (URI -> [message, names of the includes
    skipped]), for the world reader to warn about once per URI."""

    def __init__(self, source: str, search: list[str] | None = None) -> None:
        super().__init__(source, search)
        self.missing_models = {}  # model:// URI -> [message, names of the includes skipped]

    @contextmanager
    def relative_to(self, base_dir: str | None) -> Iterator[None]:
        """Relative mesh URIs read inside the block are relative to `base_dir` (a model's folder)."""
        outer, self.base_dir = self.base_dir, base_dir
        try:
            yield
        finally:
            self.base_dir = outer

    def model_folder(self, target: str) -> _ModelFolder:
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
        if os.path.isabs(path):
            searched = [path]
        else:  # the model's (or world file's) folder, then as SystemPaths::FindFile: working directory, resources
            searched = [os.path.join(self.base_dir, path)] if self.base_dir else []
            searched += model_path.find_file(path)[1]
        found = next((p for p in searched if os.path.isdir(p)), None)
        if found is None:
            return _ModelFolder(problem='no model folder at %s' % ', '.join(searched))
        return _ModelFolder(os.path.abspath(found))

    def expand_includes(self, elem: ET.Element, where: str) -> None:
        """Replaces every <include> of `elem` (a <model>) and of its nested <model>s by what it includes, as
        sdformat 9's parser does (parser.cc readXml, addNestedModel): the included model's links, joints, nested
        models, plugins and the rest come where the <include> stood, renamed NAME::old (NAME: the include's <name>,
        else the model's), posed in the include's <pose> (else the model's own), joints' and plugins' references to
        them renamed with them."""
        children = []
        for child in elem:
            if child.tag == 'include':
                children.extend(self.flattened_include(child, where))
                continue
            if child.tag == 'model':
                self.expand_includes(child, '%s model %s' % (where, quote(child.get('name', ''))))
            children.append(child)
        elem[:] = children

    def flattened_include(self, elem: ET.Element, where: str) -> list[ET.Element]:
        """The elements an <include> inside a model stands for (see expand_includes); [] when it is skipped
        (warned)."""
        uri = (elem.findtext('uri') or '').strip()
        target = uri.rstrip('/')
        where = '%s include %s' % (where, quote(uri or '(no uri)'))
        name = (elem.findtext('name') or '').strip()
        if not uri:
            self.warn(where, 'no <uri>; give <uri>model://NAME</uri>; skipped')
            return []
        if target == 'model://sun':
            self.warn(where, 'model://sun is a light; only a world holds lights; skipped')
            return []
        if target == 'model://ground_plane':
            folder, model_elem = _ModelFolder(), ET.fromstring(_GROUND_PLANE_SDF)
        else:
            found = self.included_model(target, name, where)
            if found is None:
                return []
            folder, model_elem = found
        try:
            pose = self.pose(elem if elem.find('pose') is not None else model_elem, where)
            static = elem.find('static')
            if static is not None:
                child_bool(elem, 'static', None, 'static')
        except Unusable as err:
            return self.skipped(where, err) or []
        name = name or model_elem.get('name', '')
        if not name:
            return self.skipped(where, 'the included model has no name; give the <include> a <name>') or []
        with self.relative_to(folder.path or self.base_dir):
            self.expand_includes(model_elem, where)
        if static is not None:  # the include's <static> is the model's (its first), or is added to it
            own = model_elem.find('static')
            (own if own is not None else ET.SubElement(model_elem, 'static')).text = static.text
        model_elem.extend(plugin for plugin in elem.findall('plugin'))
        replace = {child.get('name'): '%s::%s' % (name, child.get('name')) for child in model_elem
                   if child.tag in ('link', 'model', 'joint', 'frame') and child.get('name')}
        for item in model_elem.iter():  # sdformat holds values trimmed: >old< matches whatever the spaces
            if len(item) == 0 and item.text:
                item.text = item.text.strip()
        model_elem.tail = None
        model_elem = ET.fromstring(_scoped_text(ET.tostring(model_elem, encoding='unicode'), replace))
        flattened = []
        for child in model_elem:
            if child.tag == 'pose':
                continue
            if child.tag in ('link', 'model'):
                self._pose_in(child, pose)
                if folder.path and child.get(BASE_DIR) is None:
                    child.set(BASE_DIR, folder.path)
            elif child.tag == 'joint':
                self._axis_in(child, pose)
            flattened.append(child)
        return flattened

    def included_model(self, target: str, name: str, where: str) -> tuple[_ModelFolder, ET.Element] | None:
        """(_ModelFolder, <model> element) of the model an <include> names (`target`: its URI, `name`: its <name>);
        None when it is skipped: a model on no folder of the model path is collected in missing_models (one
        warning per missing model however often it is included, given with the world's others), any other
        problem warned about here."""
        if target in self.missing_models:
            self.missing_models[target][1].append(name or target)
            return None
        folder = self.model_folder(target)
        if folder.missing:
            self.missing_models[target] = [folder.problem, [name or target]]
            return None
        if folder.problem is not None:
            return self.skipped(where, folder.problem)
        model_elem = self.model_element(folder.path, where)
        return None if model_elem is None else (folder, model_elem)

    def model_element(self, folder: str, where: str) -> ET.Element | None:
        """The <model> element of the model in `folder` (model.config picks the SDF file); None when it cannot be
        read (warned)."""
        try:
            sdf_file = model_path.model_sdf_file(folder)
        except model_path.ResolveError as err:
            return self.skipped(where, err)
        try:
            root = xml_document.parse(sdf_file)
        except (ET.ParseError, OSError, ValueError, LookupError) as err:
            return self.skipped(where, '%s cannot be read as XML: %s' % (sdf_file, err))
        model_elem = root if root.tag == 'model' else root.find('model')
        if model_elem is None:
            return self.skipped(where, '%s has no <model> (only models can be included)' % sdf_file)
        return model_elem

    @staticmethod
    def _pose_in(elem, frame):
        """Writes `elem`'s <pose> (a flattened link's or nested model's) as given in `frame` (the include's pose in
        the model it is flattened into). A pose that is not 6 numbers is left for read_level to warn about."""
        child = elem.find('pose')
        try:
            own = ZERO_POSE if child is None or not (child.text or '').strip() else floats(child.text, 6, 'pose')
        except Unusable:
            return
        if child is None:
            child = ET.SubElement(elem, 'pose')
        child.text = ' '.join(repr(v) for v in as_xyz_rpy(compose(frame, own)))

    @staticmethod
    def _axis_in(joint, frame):
        """A flattened joint's axis given in its model's frame (<use_parent_model_frame>, expressed_in __model__):
        turned into the frame of the model it is flattened into."""
        for axis in joint.findall('axis'):
            xyz = axis.find('xyz')
            in_model = xyz is not None and xyz.get('expressed_in') == '__model__'
            try:
                in_model = child_bool(axis, 'use_parent_model_frame', in_model, 'use_parent_model_frame')
                if not in_model or xyz is None:
                    continue
                xyz.text = ' '.join(repr(v) for v in rotate(as_transform(frame)[1], floats(xyz.text, 3, 'axis xyz')))
            except Unusable:
                continue  # read_level warns

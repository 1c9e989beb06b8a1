"""The values of one URDF element read with UrdfError: vectors, attributes, origins, names, child text, plugins.

Pure Python: no rospy, no pybullet. What the pieces of the URDF reader (urdf_links, urdf_joints,
urdf_transmissions, urdf_sensors, urdf_extensions) read every element's values with; the checks are xml_values'
(as the SDF reader's are), the wording UrdfError's.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from racebot_sim_bridge.description import xml_values
from racebot_sim_bridge.description.urdf_model import GazeboPlugin, UrdfError, number, read_value

__all__ = ['vector', 'integer', 'boolean', 'attr_number', 'origin', 'element_name', 'child_text', 'read_plugin']


def vector(text: str | None, count: int, what: str) -> tuple[float, ...]:
    """`count` numbers, each checked in turn (the first bad one is named)."""
    return tuple(number(p, what) for p in read_value(xml_values.words, text, what, count))


def integer(text: str | None, what: str) -> int:
    return read_value(xml_values.integer, text, what)


def boolean(text: str | None, what: str) -> bool:
    return read_value(xml_values.boolean, text, what)


def attr_number(elem: ET.Element, attr: str, what: str, default: float | None = None,
                required: bool = False) -> float | None:
    """The number in attribute `attr` of `elem`; `default` when it is absent, unless it is `required`."""
    text = elem.get(attr)
    if text is None:
        if required:
            raise UrdfError('%s has no %s attribute; add %s="..."' % (what, attr, attr))
        return default
    return number(text, '%s %s' % (what, attr))


def origin(elem: ET.Element, what: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """(xyz, rpy) of the <origin> of `elem`, zeros for what is not given."""
    child = elem.find('origin')
    if child is None:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    xyz = child.get('xyz')
    rpy = child.get('rpy')
    return ((0.0, 0.0, 0.0) if xyz is None else vector(xyz, 3, what + ' <origin> xyz'),
            (0.0, 0.0, 0.0) if rpy is None else vector(rpy, 3, what + ' <origin> rpy'))


def element_name(elem: ET.Element) -> str:
    """The name attribute of a <link>, <joint> or <transmission>, which each must have."""
    name = elem.get('name')
    if not name:
        raise UrdfError('a <%s> has no name attribute; add name="..."' % elem.tag)
    return name


def child_text(elem: ET.Element, tag: str, default: str | None = None) -> str | None:
    """The stripped text of the child at `tag` (a path), `default` when there is none."""
    child = elem.find(tag)
    if child is None:
        return default
    return (child.text or '').strip()


def read_plugin(elem: ET.Element, what: str, reference: str | None) -> GazeboPlugin:
    """A <plugin> (of a <gazebo> block or of a <sensor> in one): each child's text by its tag, the first wins."""
    name = elem.get('name') or ''
    filename = elem.get('filename') or ''
    if not filename:
        raise UrdfError("%s <plugin name='%s'> has no filename attribute; add "
                        'filename="lib....so"' % (what, name))
    params = {}
    for child in elem:
        params.setdefault(child.tag, (child.text or '').strip())
    return GazeboPlugin(name, filename, params, reference, element=elem)

"""What gazebo_ros's spawn services do to a model's XML before Gazebo reads it.

Pure Python: no rospy, no pybullet. gazebo_ros_api_plugin (noetic) tells the formats apart by the
document's root element (<robot>: URDF; <sdf> or <gazebo>: SDF) and, when the request names a
robot_namespace, gives every <plugin> that has no <robotNamespace> of its own one with that namespace. Gazebo
then reads the document with TinyXML (sdformat 9, also for a URDF's <gazebo> blocks): its text is condensed as
TinyXML condenses it at the one parse here (xml_document.condense_white_space).
"""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from racebot_sim_bridge.description import xml_document

PACKAGE_PREFIX = 'package://'


def strip_xml_declaration(xml: str) -> str:
    """gazebo_ros_api_plugin's stripXmlDeclaration: the first `<? ... ?>` of the text left out, wherever it stands
    (so a blank line or a comment before `<?xml ...?>` is no error, as in Gazebo)."""
    start, end = xml.find('<?'), xml.find('?>')
    if start != -1 and end != -1 and end >= start:
        return xml[:start] + xml[end + 2:]
    return xml


def parse(xml: str | bytes) -> ET.Element | None:
    """The document's root element (its one parse per spawn), its text condensed as TinyXML condenses it, or None
    when the text is not XML."""
    try:
        text = strip_xml_declaration(xml) if isinstance(xml, str) else xml
        return xml_document.condense_white_space(ET.fromstring(text), text)
    except (ET.ParseError, ValueError, TypeError):
        return None


def format_problem(xml: str | bytes, root: ET.Element | None, wanted: str) -> str:
    """Why `xml` (parsed as `root`, None when it is not XML) is not a document of the `wanted` kind: the
    parser's words, or the root element it has."""
    if root is None:
        if not (xml.strip() if isinstance(xml, (str, bytes)) else xml):
            return 'The model_xml is empty'
        try:
            ET.fromstring(strip_xml_declaration(xml) if isinstance(xml, str) else xml)
        except (ET.ParseError, ValueError, TypeError) as err:
            return 'The model_xml is not XML (%s)' % err
    return 'The root element is <%s>; %s' % (root.tag, wanted)


def root_tag(xml: str | bytes | ET.Element) -> str | None:
    """The root element's tag (of the text, or of its parsed root element), or None when the text is not XML."""
    root = xml if isinstance(xml, ET.Element) else parse(xml)
    return None if root is None else root.tag


def is_urdf(xml: str | bytes | ET.Element) -> bool:
    return root_tag(xml) == 'robot'


def is_sdf(xml: str | bytes | ET.Element) -> bool:
    return root_tag(xml) in ('sdf', 'gazebo')


def add_robot_namespace(xml: str | ET.Element, namespace: str) -> str | ET.Element:
    """The document with <robotNamespace>namespace</robotNamespace> added to every <plugin> that
    has none; unchanged when namespace is empty. `xml`: text (a new text is returned) or a parsed
    root element (changed in place and returned)."""
    if not namespace:
        return xml
    root = xml if isinstance(xml, ET.Element) else ET.fromstring(xml)
    for plugin in root.iter('plugin'):
        if plugin.find('robotNamespace') is None:
            ET.SubElement(plugin, 'robotNamespace').text = namespace
    return root if root is xml else ET.tostring(root, encoding='unicode')


def referenced_packages(xml: str) -> list[str]:
    """The package names of the document's package:// URIs, in order, as spawn_urdf_model finds
    them: comments left out, the name being the text up to the next '/'. A package:// with no '/'
    after it ends the search (gazebo_ros logs 'Malformed package name?' and stops there too)."""
    text = re.sub(r'<!--.*?-->', '', xml, flags=re.S)
    names = []
    start = text.find(PACKAGE_PREFIX)
    while start != -1:
        begin = start + len(PACKAGE_PREFIX)
        end = text.find('/', begin)
        if end == -1:
            break
        names.append(text[begin:end])
        start = text.find(PACKAGE_PREFIX, end)
    return names

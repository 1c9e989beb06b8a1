"""Read a URDF (the expanded robot_description) into urdf_model's dataclasses: ``parse_urdf``.

Pure Python: no rospy, no pybullet. It checks what urdfdom checks (unique names, joints that name existing
links, one root, limits on revolute and prismatic joints, numeric attributes) and reads the Gazebo extensions
gazebo_ros uses: ``<gazebo reference=...>`` properties and sensors, ``<gazebo><plugin>`` blocks, and
``<transmission>`` elements as ros_control's transmission parser does. Each part has its reader: urdf_links
(links, materials), urdf_joints (joints, the tree, mimics), urdf_transmissions, urdf_extensions (``<gazebo>``
blocks) with urdf_sensors; values are read by urdf_elements with xml_values' checks (as the SDF reader's are),
worded by UrdfError. Last, sdf_reduction rewrites the extensions that name links Gazebo lumps on fixed joints,
as sdformat does, so every reader of the model sees Gazebo's names.

Anything wrong raises ``UrdfError`` saying what is wrong and what to do. Things the simulator can live with
are listed in ``RobotModel.warnings`` instead.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from racebot_sim_bridge.description import sdf_reduction, xml_document
from racebot_sim_bridge.description.urdf_extensions import read_gazebo
from racebot_sim_bridge.description.urdf_joints import check_mimics, check_tree, read_joint
from racebot_sim_bridge.description.urdf_links import read_link, read_material
from racebot_sim_bridge.description.urdf_model import RobotModel, UrdfError
from racebot_sim_bridge.description.urdf_transmissions import read_transmission

__all__ = ['parse_urdf', 'urdf_root']


def _robot(root):
    """The RobotModel of a <robot> element: links and joints (unique names, one tree), mimics, transmissions,
    <gazebo> blocks, the gazebo_ros_control plugin checked, then sdformat's reduction of the extensions."""
    if root.tag != 'robot':
        hint = ('an SDF model is spawned with spawn_model -sdf'
                if root.tag == 'sdf' else 'the robot description must start with <robot>')
        raise UrdfError('the root element is <%s>, expected <robot>; %s'
                        % (root.tag, hint))
    name = root.get('name')
    if not name:
        raise UrdfError('<robot> has no name attribute; add name="..." (e.g. name="racebot")')
    model = RobotModel(name=name)
    for elem in root.findall('material'):
        read_material(model, elem, 'robot <material>')
    for tag, read, named in (('link', lambda elem: read_link(model, elem), model.links),
                             ('joint', read_joint, model.joints)):
        for elem in root.findall(tag):
            item = read(elem)
            if item.name in named:
                raise UrdfError("%s '%s' is defined twice; %s names must be unique" % (tag, item.name, tag))
            named[item.name] = item
    check_tree(model)
    check_mimics(model)
    for elem in root.findall('transmission'):
        model.transmissions.append(read_transmission(model, elem))
    for elem in root.findall('gazebo'):
        read_gazebo(model, elem)
    plugins = [p for p in model.plugins if p.is_ros_control]
    for plugin in plugins:
        plugin.control_period  # raises UrdfError on a bad value, now rather than later
    if len(plugins) > 1:
        model.warnings.append('%d gazebo_ros_control plugins are declared; only the first (%r) is used'
                              % (len(plugins), plugins[0].name))
    sdf_reduction.reduce_extensions(model)
    return model


def parse_urdf(xml_text: str | bytes | ET.Element) -> RobotModel:
    """Parse a URDF document (str or bytes, or its root element as urdf_root gives it) into a RobotModel;
    UrdfError when unusable."""
    root = xml_text if isinstance(xml_text, ET.Element) else urdf_root(xml_text)
    return _robot(root)


def urdf_root(xml_text: str | bytes) -> ET.Element:
    """The root element of a URDF document (str or bytes): the one parse of it, for those who also need the
    XML tree (parse_urdf reads the model from it). UrdfError when it is not XML."""
    if not isinstance(xml_text, (str, bytes, bytearray)):
        raise UrdfError('the robot description must be URDF text, got %s'
                        % type(xml_text).__name__)
    if not xml_text.strip():
        raise UrdfError('the robot description is empty; set it, e.g. <param '
                        'name="robot_description" command="xacro ..."/> in the launch file')
    try:  # text condensed as TinyXML condenses it (urdfdom, sdformat and ros_control read URDF with TinyXML)
        return xml_document.condense_white_space(ET.fromstring(xml_text), xml_text)
    except ET.ParseError as err:
        # The parser's message ends with "line L, column C" (column counted from 0).
        raise UrdfError('the robot description is not valid XML: %s; if it is a .xacro file, '
                        'run it through xacro first' % err) from None
    except (ValueError, LookupError) as err:
        raise UrdfError('the robot description could not be read as XML: %s' % err) from None


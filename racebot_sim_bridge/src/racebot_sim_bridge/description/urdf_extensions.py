"""A URDF's ``<gazebo>`` blocks read into a RobotModel, as sdformat's URDF reader reads them (part of urdf_reader).

Pure Python: no rospy, no pybullet. A block without ``reference`` gives model plugins (and the SDF elements
sdf_reduction rewrites); a ``<gazebo reference=...>`` block gives the link's or joint's properties
(RobotModel.gazebo_refs: numbers, switches as booleans, the rest as text), its sensors (urdf_sensors), its
plugins and visual plugins. What sdformat would ignore is warned about in RobotModel.warnings.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from racebot_sim_bridge.description.urdf_elements import read_plugin
from racebot_sim_bridge.description.urdf_model import KEEP_FIXED_JOINT, GazeboElement, RobotModel
from racebot_sim_bridge.description.urdf_sensors import read_sensor

__all__ = ['read_gazebo', 'EXTENSION_VALUES', 'EXTENSION_FLAGS', 'REDUCED_ELEMENTS']

# The <gazebo reference> elements sdformat's URDF reader knows (parser_urdf.cc, ParseSDFExtension).
# It reads them through GetKeyValueAsString: the `value` attribute when there is one (the old style,
# <mu1 value="1.0"/>), else the text. Any other element it copies into the SDF as written.
EXTENSION_VALUES = frozenset((
    'material', 'static', 'turnGravityOff', 'dampingFactor', 'maxVel', 'minDepth', 'mu1', 'mu2', 'fdir1',
    'kp', 'kd', 'selfCollide', 'maxContacts', 'laserRetro', 'springReference', 'springStiffness', 'stopCfm',
    'stopErp', 'fudgeFactor', 'provideFeedback', 'cfmDamping', 'implicitSpringDamper',
    'disableFixedJointLumping', 'preserveFixedJoint'))
# Those of them that are switches, kept as booleans.
EXTENSION_FLAGS = frozenset((
    'static', 'turnGravityOff', 'selfCollide', 'provideFeedback', 'cfmDamping', 'implicitSpringDamper',
    'disableFixedJointLumping', 'preserveFixedJoint'))
# The SDF elements of a <gazebo> block whose link names or pose sdformat rewrites when it lumps a link
# (sdf_reduction); kept as written in RobotModel.gazebo_elements.
REDUCED_ELEMENTS = frozenset(('light', 'projector', 'gripper', 'joint'))


def _extension_text(elem):
    """The value of a leaf <gazebo reference> element as sdformat reads it."""
    if elem.tag in EXTENSION_VALUES and elem.get('value') is not None:
        return elem.get('value').strip()
    return (elem.text or '').strip()


def _extension_flag(tag, text):
    """sdformat's reading of a switch: 'true', 'yes' (any case) or '1' is on, anything else off;
    except turnGravityOff, which is on unless 'false', 'no' or '0'."""
    if tag == 'turnGravityOff':
        return not (text.lower() in ('false', 'no') or text == '0')
    return text.lower() in ('true', 'yes') or text == '1'


def read_gazebo(model: RobotModel, elem: ET.Element) -> None:
    """Reads a <gazebo> block into `model` (its links and joints already read)."""
    reference = elem.get('reference')
    if reference is None:
        _model_static(model, elem)
        for child in elem:
            if child.tag == 'plugin':
                model.plugins.append(read_plugin(child, '<gazebo>', None))
            elif child.tag == 'sensor':
                model.warnings.append("<gazebo> sensor '%s' has no reference link; add "
                                      '<gazebo reference="link_name">; skipped' % child.get('name'))
            elif child.tag in REDUCED_ELEMENTS:
                model.gazebo_elements.append(GazeboElement(None, child))
        return
    what = "<gazebo reference='%s'>" % reference
    if reference not in model.links and reference not in model.joints:
        model.warnings.append("%s names no link or joint of the robot; its settings are ignored"
                              % what)
        return
    properties = model.gazebo_refs.setdefault(reference, {})
    for child in elem:
        if child.tag == 'sensor':
            model.sensors.append(read_sensor(child, reference))
        elif child.tag == 'plugin':
            model.plugins.append(read_plugin(child, what, reference))
        elif child.tag in REDUCED_ELEMENTS:
            model.gazebo_elements.append(GazeboElement(reference, child))
        elif child.tag == 'visual':  # a visual plugin (gazebo_ros_video): run with the model's plugins
            for plugin in child.findall('plugin'):
                model.plugins.append(read_plugin(plugin, what + ' <visual>', reference))
        elif len(child) == 0:
            _property(model, properties, child, what, reference)


def _model_static(model, elem):
    """The model's <static> as sdformat 9 reads it (parser_urdf.cc): each <gazebo> block without reference is an
    extension whose static flag is its <static> (false without one), and InsertSDFExtensionRobot writes every such
    block's flag into the model in turn, so the last block decides (sdformat warns of the overwrite)."""
    flag = False
    for child in elem.findall('static'):
        flag = _extension_flag('static', _extension_text(child))
    if model.static and not flag:
        model.warnings.append('a <gazebo> block without reference and without <static>true</static> follows one '
                              'with it: sdformat takes the last block\'s <static> (false), so the model is not '
                              'static; put <static>true</static> in the last <gazebo> block')
    model.static = flag


def _property(model, properties, child, what, reference):
    """A leaf element of the <gazebo reference> block of `reference` into its `properties`."""
    text = _extension_text(child)
    if child.tag in EXTENSION_FLAGS:
        properties[child.tag] = _extension_flag(child.tag, text)
        if child.tag in KEEP_FIXED_JOINT and reference not in model.joints:
            _warn_keep_on_link(model, what, child.tag, reference)
        return
    try:
        value = float(text)
        properties[child.tag] = value if math.isfinite(value) else text
    except ValueError:
        properties[child.tag] = text
    if child.tag in ('mu1', 'mu2') and not (isinstance(properties[child.tag], float)
                                            and properties[child.tag] >= 0):
        model.warnings.append("%s <%s>%s</%s>: a friction coefficient is a number >= 0; ignored"
                              % (what, child.tag, text, child.tag))
        del properties[child.tag]


def _warn_keep_on_link(model, what, tag, link):
    """Gazebo reads preserveFixedJoint / disableFixedJointLumping on joint references only."""
    joint = model.parent_joint(link)
    hint = ('write it as <gazebo reference="%s"> (the fixed joint above it)' % joint.name
            if joint is not None else 'it names the root link, which has no joint above it')
    model.warnings.append('%s <%s>: Gazebo reads this on a fixed joint\'s reference, not a link\'s, so the link is '
                          'still lumped; %s' % (what, tag, hint))

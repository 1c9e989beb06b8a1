"""A URDF's <transmission>s as ros_control's transmission parser reads them (part of urdf_reader.parse_urdf).

Pure Python: no rospy, no pybullet. Each joint and actuator with its hardware interfaces, normalised to
``hardware_interface/...`` (the old bare spelling warned about in RobotModel.warnings), an actuator's
mechanical reduction. Which joints exist is not checked here: that is gazebo_ros_control's business
(robot_hw_sim), as urdfdom ignores transmissions.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from racebot_sim_bridge.description.urdf_elements import child_text, element_name
from racebot_sim_bridge.description.urdf_model import (RobotModel, Transmission, UrdfError, normalise_interface,
                                                       number)

__all__ = ['read_transmission']


def _interfaces(model, elem, what):
    names = []
    for child in elem.findall('hardwareInterface'):
        raw = (child.text or '').strip()
        if not raw:
            raise UrdfError('%s has an empty <hardwareInterface>; write e.g. '
                            'hardware_interface/EffortJointInterface' % what)
        if '/' not in raw:
            model.warnings.append("%s: deprecated interface spelling '%s'; write "
                                  "'hardware_interface/%s'" % (what, raw, raw))
        names.append(normalise_interface(raw))
    return names


def read_transmission(model: RobotModel, elem: ET.Element) -> Transmission:
    """The Transmission of a <transmission> (warnings into `model`)."""
    name = element_name(elem)
    what = "transmission '%s'" % name
    kind = child_text(elem, 'type') or elem.get('type') or ''
    transmission = Transmission(name, kind)
    for joint in elem.findall('joint'):
        joint_name = joint.get('name')
        if not joint_name:
            raise UrdfError('%s has a <joint> without a name; add name="..."' % what)
        # A joint that does not exist is gazebo_ros_control's business, not the URDF's (urdfdom
        # ignores transmissions): robot_hw_sim.hardware_joints() raises for it, and the robot is spawned
        # without a controller manager, as in Gazebo.
        transmission.joints.append(
            (joint_name, _interfaces(model, joint, "%s joint '%s'" % (what, joint_name))))
    for actuator in elem.findall('actuator'):
        actuator_name = actuator.get('name') or ''
        where = "%s actuator '%s'" % (what, actuator_name)
        reduction = child_text(actuator, 'mechanicalReduction')
        transmission.actuators.append(
            (actuator_name, _interfaces(model, actuator, where),
             1.0 if not reduction else number(reduction, where + ' <mechanicalReduction>')))
    return transmission

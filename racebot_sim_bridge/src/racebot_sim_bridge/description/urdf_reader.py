"""Read a URDF (the expanded robot_description) into urdf_model's dataclasses: ``parse_urdf``.

Pure Python: no rospy, no pybullet. It checks what urdfdom checks (unique names, joints that name existing
links, one root, limits on revolute and prismatic joints, numeric attributes) and reads the Gazebo extensions
gazebo_ros uses: ``<gazebo reference=...>`` properties and sensors, ``<gazebo><plugin>`` blocks, and
``<transmission>`` elements as ros_control's transmission parser does. Values are checked by xml_values (as
the SDF reader's are) and worded by UrdfError. Last, sdf_reduction rewrites the extensions that name links Gazebo
lumps on fixed joints, as sdformat does, so every reader of the model sees Gazebo's names.

Anything wrong raises ``UrdfError`` saying what is wrong and what to do. Things the simulator can live with
are listed in ``RobotModel.warnings`` instead.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from racebot_sim_bridge.description import sdf_reduction, xml_values
from racebot_sim_bridge.description.geometry import ShapeKind
from racebot_sim_bridge.description.urdf_model import (
    JOINT_TYPES, KEEP_FIXED_JOINT, CameraSpec, Dynamics, GazeboElement, GazeboPlugin, Geometry, ImuSpec, Inertial,
    Joint, Limit, Link, Mimic, RaySpec, RobotModel, SensorSpec, Transmission, UrdfError, normalise_interface,
    read_value)
from racebot_sim_bridge.description.urdf_model import number as _number

__all__ = ['parse_urdf', 'urdf_root']


# ---------------------------------------------------------------------------------------
# Value parsing
# ---------------------------------------------------------------------------------------

def _vector(text, count, what):
    """`count` numbers, each checked in turn (the first bad one is named)."""
    return tuple(_number(p, what) for p in read_value(xml_values.words, text, what, count))


def _integer(text, what):
    return read_value(xml_values.integer, text, what)


def _boolean(text, what):
    return read_value(xml_values.boolean, text, what)


# The <gazebo reference> elements sdformat's URDF reader knows (parser_urdf.cc, ParseSDFExtension).
# It reads them through GetKeyValueAsString: the `value` attribute when there is one (the old style,
# <mu1 value="1.0"/>), else the text. Any other element it copies into the SDF as written.
# The shapes a URDF <geometry> may hold (urdfdom; a <plane> is SDF only).
URDF_SHAPES = (ShapeKind.BOX, ShapeKind.CYLINDER, ShapeKind.SPHERE, ShapeKind.MESH)

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


def _attr_number(elem, attr, what, default=None, required=False):
    text = elem.get(attr)
    if text is None:
        if required:
            raise UrdfError('%s has no %s attribute; add %s="..."' % (what, attr, attr))
        return default
    return _number(text, '%s %s' % (what, attr))


def _origin(elem, what):
    origin = elem.find('origin')
    if origin is None:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    xyz = origin.get('xyz')
    rpy = origin.get('rpy')
    return ((0.0, 0.0, 0.0) if xyz is None else _vector(xyz, 3, what + ' <origin> xyz'),
            (0.0, 0.0, 0.0) if rpy is None else _vector(rpy, 3, what + ' <origin> rpy'))


def _name(elem):
    """The name attribute of a <link>, <joint> or <transmission>, which each must have."""
    name = elem.get('name')
    if not name:
        raise UrdfError('a <%s> has no name attribute; add name="..."' % elem.tag)
    return name


def _child_text(elem, tag, default=None):
    child = elem.find(tag)
    if child is None:
        return default
    return (child.text or '').strip()


# ---------------------------------------------------------------------------------------
# The reader
# ---------------------------------------------------------------------------------------

class _UrdfReader:
    def __init__(self, root):
        self.root = root
        self.model = None

    def warn(self, message):
        self.model.warnings.append(message)

    def read(self):
        root = self.root
        if root.tag != 'robot':
            hint = ('an SDF model is spawned with spawn_model -sdf'
                    if root.tag == 'sdf' else 'the robot description must start with <robot>')
            raise UrdfError('the root element is <%s>, expected <robot>; %s'
                            % (root.tag, hint))
        name = root.get('name')
        if not name:
            raise UrdfError('<robot> has no name attribute; add name="..." (e.g. name="racebot")')
        self.model = RobotModel(name=name)
        for elem in root.findall('material'):
            self.material(elem, 'robot <material>')
        for tag, read, named in (('link', self.link, self.model.links), ('joint', self.joint, self.model.joints)):
            for elem in root.findall(tag):
                item = read(elem)
                if item.name in named:
                    raise UrdfError("%s '%s' is defined twice; %s names must be unique" % (tag, item.name, tag))
                named[item.name] = item
        self.tree()
        self.mimics()
        for elem in root.findall('transmission'):
            self.model.transmissions.append(self.transmission(elem))
        for elem in root.findall('gazebo'):
            self.gazebo(elem)
        plugins = [p for p in self.model.plugins if p.is_ros_control]
        for plugin in plugins:
            plugin.control_period  # raises UrdfError on a bad value, now rather than later
        if len(plugins) > 1:
            self.warn('%d gazebo_ros_control plugins are declared; only the first (%r) is used'
                      % (len(plugins), plugins[0].name))
        sdf_reduction.reduce_extensions(self.model)
        return self.model

    # -- links ------------------------------------------------------------------------

    def material(self, elem, what):
        """The rgba of a <material> (looked up by name if it has no colour), or None."""
        name = elem.get('name', '')
        color = elem.find('color')
        rgba = None
        if color is not None:
            rgba = _vector(color.get('rgba'), 4,
                           "%s '%s' <color> rgba" % (what, name))
        if name and rgba is not None and name not in self.model.materials:
            self.model.materials[name] = rgba
        if rgba is None and name:
            rgba = self.model.materials.get(name)
        return name, rgba

    def geometry(self, elem, what, visual):
        xyz, rpy = _origin(elem, what)
        geometry = elem.find('geometry')
        shapes = list(geometry) if geometry is not None else []
        if not shapes:
            raise UrdfError('%s has no <geometry> shape; add <geometry><box size="..."/>'
                            '</geometry> (or cylinder, sphere, mesh)' % what)
        shape = shapes[0]
        if shape.tag not in URDF_SHAPES:
            raise UrdfError('%s: unknown geometry <%s>; use box, cylinder, sphere or mesh'
                            % (what, shape.tag))
        result = Geometry(shape.tag, origin_xyz=xyz, origin_rpy=rpy, name=elem.get('name'))
        where = '%s <%s>' % (what, shape.tag)
        if shape.tag == 'box':
            result.size = _vector(shape.get('size'), 3, where + ' size')
        elif shape.tag == 'cylinder':
            result.radius = _attr_number(shape, 'radius', where, required=True)
            result.length = _attr_number(shape, 'length', where, required=True)
        elif shape.tag == 'sphere':
            result.radius = _attr_number(shape, 'radius', where, required=True)
        else:  # mesh
            result.filename = shape.get('filename')
            if not result.filename:
                raise UrdfError('%s has no filename attribute; add filename="package://..."'
                                % where)
            scale = shape.get('scale')
            result.scale = (1.0, 1.0, 1.0) if scale is None else _vector(scale, 3,
                                                                        where + ' scale')
        if visual:
            material = elem.find('material')
            if material is not None:
                result.material, result.rgba = self.material(material, what + ' <material>')
                if result.rgba is None and material.find('texture') is None and result.material:
                    self.warn("%s: material '%s' is not defined at the robot level and has no "
                              "<color>; drawn in the default colour" % (what, result.material))
        return result

    def link(self, elem):
        name = _name(elem)
        what = "link '%s'" % name
        link = Link(name)
        inertial = elem.find('inertial')
        if inertial is not None:
            mass = inertial.find('mass')
            if mass is None:
                raise UrdfError('%s <inertial> has no <mass>; add <mass value="..."/>' % what)
            xyz, rpy = _origin(inertial, what + ' <inertial>')
            inertia = inertial.find('inertia')
            if inertia is None:
                raise UrdfError('%s <inertial> has no <inertia>; add <inertia ixx="..." ixy="0" '
                                'ixz="0" iyy="..." iyz="0" izz="..."/>' % what)
            values = {key: _attr_number(inertia, key, what + ' <inertia>', required=True)
                      for key in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')}
            link.inertial = Inertial(
                _attr_number(mass, 'value', what + ' <mass>', required=True), xyz, rpy, **values)
        for index, child in enumerate(elem.findall('collision')):
            link.collisions.append(self.geometry(child, '%s <collision> #%d' % (what, index + 1),
                                                 visual=False))
        for index, child in enumerate(elem.findall('visual')):
            link.visuals.append(self.geometry(child, '%s <visual> #%d' % (what, index + 1),
                                              visual=True))
        return link

    # -- joints -----------------------------------------------------------------------

    def joint(self, elem):
        name = _name(elem)
        what = "joint '%s'" % name
        kind = elem.get('type')
        if kind not in JOINT_TYPES:
            raise UrdfError('%s has type %r; use one of %s'
                            % (what, kind, ', '.join(JOINT_TYPES)))
        ends = {}
        for tag in ('parent', 'child'):
            end = elem.find(tag)
            if end is None or not end.get('link'):
                raise UrdfError('%s has no <%s link="..."/>; add it' % (what, tag))
            ends[tag] = end.get('link')
        xyz, rpy = _origin(elem, what)
        joint = Joint(name, kind, ends['parent'], ends['child'], xyz, rpy)
        axis = elem.find('axis')
        if axis is not None and axis.get('xyz') is not None and kind not in ('fixed', 'floating'):
            joint.axis = _vector(axis.get('xyz'), 3, what + ' <axis> xyz')
            if not any(joint.axis):
                raise UrdfError('%s <axis> is the zero vector; give a direction, e.g. "0 1 0"'
                                % what)
        limit = elem.find('limit')
        if limit is not None:
            where = what + ' <limit>'
            joint.limit = Limit(_attr_number(limit, 'lower', where, 0.0),
                                _attr_number(limit, 'upper', where, 0.0),
                                _attr_number(limit, 'effort', where, required=True),
                                _attr_number(limit, 'velocity', where, required=True))
        elif kind in ('revolute', 'prismatic'):
            raise UrdfError('%s is %s but has no <limit>; add <limit lower="..." upper="..." '
                            'effort="..." velocity="..."/> or make it continuous' % (what, kind))
        dynamics = elem.find('dynamics')
        if dynamics is not None:
            where = what + ' <dynamics>'
            joint.dynamics = Dynamics(_attr_number(dynamics, 'damping', where, 0.0),
                                      _attr_number(dynamics, 'friction', where, 0.0))
        mimic = elem.find('mimic')
        if mimic is not None:
            where = what + ' <mimic>'
            if not mimic.get('joint'):
                raise UrdfError('%s has no joint attribute; add joint="the joint it follows"' % where)
            joint.mimic = Mimic(mimic.get('joint'), _attr_number(mimic, 'multiplier', where, 1.0),
                                _attr_number(mimic, 'offset', where, 0.0))
        return joint

    def mimics(self):
        """Checks the <mimic> joints racebot drives (Gazebo 11 ignores them): one it cannot drive is warned
        about; a loop of them is refused, as no position satisfies it."""
        joints = self.model.joints
        for joint in joints.values():
            if joint.mimic is None:
                continue
            leader = joints.get(joint.mimic.joint)
            if leader is None:
                self.warn("joint '%s' <mimic joint='%s'>: the URDF has no such joint; the joint moves freely, as "
                          "in Gazebo" % (joint.name, joint.mimic.joint))
            elif joint.name not in self.model.mimics():
                self.warn("joint '%s' (%s) <mimic joint='%s'> (%s): racebot drives a <mimic> only between revolute, "
                          "continuous or prismatic joints; it is ignored, as Gazebo ignores it"
                          % (joint.name, joint.type, leader.name, leader.type))
        mimics = self.model.mimics()
        for start in mimics:
            path = [start]
            while path[-1] in mimics:
                path.append(mimics[path[-1]].joint)
                if path[-1] in path[:-1]:
                    loop = path[path.index(path[-1]):]
                    if start == loop[0]:
                        raise UrdfError(
                            'the <mimic> joints form a loop (%s): racebot drives each <mimic> joint from the joint it '
                            'names (Gazebo 11 ignores <mimic>), and no position satisfies a loop; let one of them '
                            'mimic none' % ' mimics '.join("'%s'" % n for n in loop))
                    break

    def tree(self):
        links, joints = self.model.links, self.model.joints
        if not links:
            raise UrdfError("robot '%s' has no links (so no root link); add at least one "
                            '<link name="..."/>' % self.model.name)
        parent_of = {}
        for joint in joints.values():
            for role, link in (('parent', joint.parent), ('child', joint.child)):
                if link not in links:
                    raise UrdfError(
                        "joint '%s': %s link '%s' does not exist; add <link name=\"%s\"/> or "
                        'fix the joint\'s <%s link="..."/>'
                        % (joint.name, role, link, link, role))
            if joint.parent == joint.child:
                raise UrdfError("joint '%s' connects link '%s' to itself; its parent and child "
                                'must differ' % (joint.name, joint.child))
            if joint.child in parent_of:
                raise UrdfError("link '%s' is the child of two joints ('%s' and '%s'); a link "
                                'has at most one parent joint'
                                % (joint.child, parent_of[joint.child], joint.name))
            parent_of[joint.child] = joint.name
        roots = [name for name in links if name not in parent_of]
        if not roots:
            raise UrdfError('no root link: every link is the child of a joint, so the joints '
                            'form a loop; remove a joint to make a tree')
        if len(roots) > 1:
            raise UrdfError('several root links (%s): every link but one must be the child of '
                            'a joint; connect them with joints (e.g. fixed ones)'
                            % ', '.join("'%s'" % r for r in roots))
        reached, stack = {roots[0]}, [roots[0]]
        while stack:
            for child in self.model.children(stack.pop()):
                if child not in reached:
                    reached.add(child)
                    stack.append(child)
        loose = [name for name in links if name not in reached]
        if loose:
            raise UrdfError('links %s are not connected to the root link %r: their joints form '
                            'a loop; remove a joint to make a tree'
                            % (', '.join("'%s'" % n for n in loose), roots[0]))
        self.model.root_link = roots[0]

    # -- transmissions ----------------------------------------------------------------

    def interfaces(self, elem, what):
        names = []
        for child in elem.findall('hardwareInterface'):
            raw = (child.text or '').strip()
            if not raw:
                raise UrdfError('%s has an empty <hardwareInterface>; write e.g. '
                                'hardware_interface/EffortJointInterface' % what)
            if '/' not in raw:
                self.warn("%s: deprecated interface spelling '%s'; write "
                          "'hardware_interface/%s'" % (what, raw, raw))
            names.append(normalise_interface(raw))
        return names

    def transmission(self, elem):
        name = _name(elem)
        what = "transmission '%s'" % name
        kind = _child_text(elem, 'type') or elem.get('type') or ''
        transmission = Transmission(name, kind)
        for joint in elem.findall('joint'):
            joint_name = joint.get('name')
            if not joint_name:
                raise UrdfError('%s has a <joint> without a name; add name="..."' % what)
            # A joint that does not exist is gazebo_ros_control's business, not the URDF's (urdfdom
            # ignores transmissions): robot_hw_sim.hardware_joints() raises for it, and the robot is spawned
            # without a controller manager, as in Gazebo.
            transmission.joints.append(
                (joint_name, self.interfaces(joint, "%s joint '%s'" % (what, joint_name))))
        for actuator in elem.findall('actuator'):
            actuator_name = actuator.get('name') or ''
            where = "%s actuator '%s'" % (what, actuator_name)
            reduction = _child_text(actuator, 'mechanicalReduction')
            transmission.actuators.append(
                (actuator_name, self.interfaces(actuator, where),
                 1.0 if not reduction else _number(reduction, where + ' <mechanicalReduction>')))
        return transmission

    # -- gazebo extensions ------------------------------------------------------------

    def plugin(self, elem, what, reference):
        name = elem.get('name') or ''
        filename = elem.get('filename') or ''
        if not filename:
            raise UrdfError("%s <plugin name='%s'> has no filename attribute; add "
                            'filename="lib....so"' % (what, name))
        params = {}
        for child in elem:
            params.setdefault(child.tag, (child.text or '').strip())
        return GazeboPlugin(name, filename, params, reference, element=elem)

    def gazebo(self, elem):
        reference = elem.get('reference')
        if reference is None:
            for child in elem:
                if child.tag == 'plugin':
                    self.model.plugins.append(self.plugin(child, '<gazebo>', None))
                elif child.tag == 'sensor':
                    self.warn("<gazebo> sensor '%s' has no reference link; add "
                              '<gazebo reference="link_name">; skipped' % child.get('name'))
                elif child.tag in REDUCED_ELEMENTS:
                    self.model.gazebo_elements.append(GazeboElement(None, child))
            return
        what = "<gazebo reference='%s'>" % reference
        if reference not in self.model.links and reference not in self.model.joints:
            self.warn("%s names no link or joint of the robot; its settings are ignored"
                      % what)
            return
        properties = self.model.gazebo_refs.setdefault(reference, {})
        for child in elem:
            if child.tag == 'sensor':
                self.model.sensors.append(self.sensor(child, reference))
            elif child.tag == 'plugin':
                self.model.plugins.append(self.plugin(child, what, reference))
            elif child.tag in REDUCED_ELEMENTS:
                self.model.gazebo_elements.append(GazeboElement(reference, child))
            elif child.tag == 'visual':  # a visual plugin (gazebo_ros_video): run with the model's plugins
                for plugin in child.findall('plugin'):
                    self.model.plugins.append(self.plugin(plugin, what + ' <visual>', reference))
            elif len(child) == 0:
                text = _extension_text(child)
                if child.tag in EXTENSION_FLAGS:
                    properties[child.tag] = _extension_flag(child.tag, text)
                    if child.tag in KEEP_FIXED_JOINT and reference not in self.model.joints:
                        self._warn_keep_on_link(what, child.tag, reference)
                    continue
                try:
                    value = float(text)
                    properties[child.tag] = value if math.isfinite(value) else text
                except ValueError:
                    properties[child.tag] = text
                if child.tag in ('mu1', 'mu2') and not (isinstance(properties[child.tag], float)
                                                        and properties[child.tag] >= 0):
                    self.warn("%s <%s>%s</%s>: a friction coefficient is a number >= 0; ignored"
                              % (what, child.tag, text, child.tag))
                    del properties[child.tag]

    def _warn_keep_on_link(self, what, tag, link):
        """Gazebo reads preserveFixedJoint / disableFixedJointLumping on joint references only."""
        joint = self.model.parent_joint(link)
        hint = ('write it as <gazebo reference="%s"> (the fixed joint above it)' % joint.name
                if joint is not None else 'it names the root link, which has no joint above it')
        self.warn('%s <%s>: Gazebo reads this on a fixed joint\'s reference, not a link\'s, so the link is '
                  'still lumped; %s' % (what, tag, hint))

    def sensor(self, elem, reference):
        name = elem.get('name')
        kind = elem.get('type')
        what = "sensor '%s' (on '%s')" % (name, reference)
        if not name or not kind:
            raise UrdfError('a <sensor> on %r lacks a %s attribute; add it (type is ray, '
                            'gpu_ray, camera, depth, imu, ...)'
                            % (reference, 'name' if not name else 'type'))
        spec = SensorSpec(name, kind, reference)
        text = _child_text(elem, 'update_rate')
        if text is not None:
            spec.update_rate = _number(text, what + ' <update_rate>')
            if spec.update_rate < 0.0:
                raise UrdfError('%s <update_rate> must be >= 0 Hz, got %s' % (what, text))
        for tag in ('always_on', 'visualize'):
            text = _child_text(elem, tag)
            if text is not None:
                setattr(spec, tag, _boolean(text, '%s <%s>' % (what, tag)))
        text = _child_text(elem, 'pose')
        if text:
            spec.pose = _vector(text, 6, what + ' <pose>')
        ray = elem.find('ray')
        if ray is None:
            ray = elem.find('lidar')
        if ray is not None:
            spec.ray = self.ray(ray, what)
        spec.cameras = [self.camera(camera, what) for camera in elem.findall('camera')]
        if spec.cameras:
            spec.camera = spec.cameras[0]
        contact = elem.find('contact')
        if contact is not None:
            spec.contact_collisions = [(c.text or '').strip() for c in contact.findall('collision')]
        imu = elem.find('imu')
        if imu is not None or kind == 'imu':
            spec.imu = self.imu(imu, what)
        for plugin in elem.findall('plugin'):
            spec.plugins.append(self.plugin(plugin, what, reference))
        return spec

    @staticmethod
    def _fill(target, elem, fields, what, convert=_number):
        """Set attributes of ``target`` from child paths of ``elem`` that are present."""
        if elem is None:
            return
        for attr, path in fields:
            text = _child_text(elem, path)
            if text is not None:
                setattr(target, attr, convert(text, '%s <%s>' % (what, path)))

    def noise(self, elem, what):
        """(type, mean, stddev) of a <noise> element (child elements or SDF 1.6 type attr)."""
        if elem is None:
            return 'none', 0.0, 0.0
        kind = _child_text(elem, 'type') or elem.get('type') or 'none'
        mean = _child_text(elem, 'mean')
        stddev = _child_text(elem, 'stddev')
        return (kind,
                0.0 if mean is None else _number(mean, what + ' <noise><mean>'),
                0.0 if stddev is None else _number(stddev, what + ' <noise><stddev>'))

    def noise_with_bias(self, elem, what):
        """(mean, stddev, bias_mean, bias_stddev) of a <noise> element, zeros without one."""
        if elem is None:
            return (0.0, 0.0, 0.0, 0.0)
        values = []
        for key in ('mean', 'stddev', 'bias_mean', 'bias_stddev'):
            text = _child_text(elem, key)
            values.append(0.0 if text is None else _number(text, '%s <%s>' % (what, key)))
        return tuple(values)

    def ray(self, elem, what):
        spec = RaySpec()
        what = what + ' <%s>' % elem.tag
        self._fill(spec, elem, [('samples', 'scan/horizontal/samples'),
                                ('vertical_samples', 'scan/vertical/samples')],
                   what, _integer)
        self._fill(spec, elem, [
            ('resolution', 'scan/horizontal/resolution'),
            ('min_angle', 'scan/horizontal/min_angle'),
            ('max_angle', 'scan/horizontal/max_angle'),
            ('vertical_resolution', 'scan/vertical/resolution'),
            ('vertical_min_angle', 'scan/vertical/min_angle'),
            ('vertical_max_angle', 'scan/vertical/max_angle'),
            ('range_min', 'range/min'),
            ('range_max', 'range/max'),
            ('range_resolution', 'range/resolution'),
        ], what)
        if spec.samples < 1:
            raise UrdfError('%s needs at least 1 sample, got %d' % (what, spec.samples))
        spec.noise_type, spec.noise_mean, spec.noise_stddev = self.noise(elem.find('noise'),
                                                                         what)
        return spec

    def camera(self, elem, what):
        spec = CameraSpec(name=elem.get('name') or '')
        what = what + ' <camera>'
        self._fill(spec, elem, [('width', 'image/width'), ('height', 'image/height')],
                   what, _integer)
        self._fill(spec, elem, [('horizontal_fov', 'horizontal_fov'),
                                ('clip_near', 'clip/near'), ('clip_far', 'clip/far')], what)
        spec.format = _child_text(elem, 'image/format') or spec.format
        text = _child_text(elem, 'pose')
        if text:
            spec.pose = _vector(text, 6, what + ' <pose>')
        if spec.width < 1 or spec.height < 1:
            raise UrdfError('%s image must be at least 1 x 1 pixels, got %d x %d'
                            % (what, spec.width, spec.height))
        spec.noise_type, spec.noise_mean, spec.noise_stddev = self.noise(elem.find('noise'),
                                                                         what)
        distortion = elem.find('distortion')
        if distortion is not None:
            values = []
            for key in ('k1', 'k2', 'k3', 'p1', 'p2'):
                text = _child_text(distortion, key)
                values.append(_number(text, '%s <distortion><%s>' % (what, key)) if text else 0.0)
            spec.distortion = tuple(values)
        return spec

    def imu(self, elem, what):
        spec = ImuSpec()
        if elem is None:
            return spec
        what = what + ' <imu>'
        for attr, group, old_form in (('angular_velocity_noise', 'angular_velocity', 'noise/rate'),
                                      ('linear_acceleration_noise', 'linear_acceleration', 'noise/accel')):
            shared = elem.find(old_form)
            axes = []
            for axis in 'xyz':
                path = '%s/%s/noise' % (group, axis)
                noise = elem.find(path)
                if noise is None and shared is not None:
                    noise, path = shared, old_form
                axes.append(self.noise_with_bias(noise, '%s <%s>' % (what, path)))
            setattr(spec, attr, tuple(axes))
        return spec


def parse_urdf(xml_text: str | bytes | ET.Element) -> RobotModel:
    """Parse a URDF document (str or bytes, or its root element as urdf_root gives it) into a RobotModel;
    UrdfError when unusable."""
    root = xml_text if isinstance(xml_text, ET.Element) else urdf_root(xml_text)
    return _UrdfReader(root).read()


def urdf_root(xml_text: str | bytes) -> ET.Element:
    """The root element of a URDF document (str or bytes): the one parse of it, for those who also need the
    XML tree (parse_urdf reads the model from it). UrdfError when it is not XML."""
    if not isinstance(xml_text, (str, bytes, bytearray)):
        raise UrdfError('the robot description must be URDF text, got %s'
                        % type(xml_text).__name__)
    if not xml_text.strip():
        raise UrdfError('the robot description is empty; set it, e.g. <param '
                        'name="robot_description" command="xacro ..."/> in the launch file')
    try:
        return ET.fromstring(xml_text)
    except ET.ParseError as err:
        # The parser's message ends with "line L, column C" (column counted from 0).
        raise UrdfError('the robot description is not valid XML: %s; if it is a .xacro file, '
                        'run it through xacro first' % err) from None
    except (ValueError, LookupError) as err:
        raise UrdfError('the robot description could not be read as XML: %s' % err) from None


"""sdformat's fixed-joint reduction of the <gazebo> extensions, applied to a parsed RobotModel.

No rospy, no pybullet. When Gazebo 11 reads a URDF, sdformat 9 (src/parser_urdf.cc, branch sdf9) lumps every
link on a fixed joint into its parent (urdf_lumping does that to the shapes and masses) and rewrites the
<gazebo> extensions that name it, so that plugins and sensors see that parent. ``reduce_extensions`` does the
same to a RobotModel, rule by rule, in ReduceFixedJoints' order: depth first from the root, a link's fixed
children (in joint-name order, urdfdom's) before the link itself, its moving children after. For each link L
reduced into its parent P through the fixed joint origin J (the joint stays when its <gazebo reference> sets
preserveFixedJoint or disableFixedJointLumping, or when P is named ``world``):

1. ReduceSDFExtensionToParent: every block of <gazebo reference="L"> moves to P; its reduction transform
   becomes J (replaced, not composed, at each step).
2. ReduceSDFExtensionElementTransformReduction, for those moved blocks only: the <pose> of a <sensor>,
   <light> or <projector> becomes J * pose (a missing one J; one with a relative_to attribute is left).
3. ReduceSDFExtensionFrameReplace, for the elements of EVERY block (model-level ones, other links' and
   joints', not the <plugin> inside a <sensor>):
   - ContactSensorFrameReplace: a <sensor>'s first <contact><collision>, when it is L_collision, becomes
     P_collision_L (a name no collision has: Gazebo calls the lumped one P_fixed_joint_lump__L_collision_N),
     moved to the end of the list;
   - PluginFrameReplace, for <bodyName> then <frameName> of a <plugin>: when it is L it becomes P, and the
     plugin gets <xyzOffset> and <rpyOffset> = J * (xyzOffset, rpyOffset), an absent one taken from the
     block's reduction transform (identity for a block never moved: so a plugin in L's own block counts J
     twice), and <ignition::corrected_offsets>1. When both name L the offsets compose J twice too;
   - ProjectorFrameReplace: <projector>L/name</projector> of any element becomes P/name;
   - GripperFrameReplace: a <gripper>'s <gripper_link> and <palm_link> naming L become P;
   - JointFrameReplace: an SDF <joint>'s <parent> and <child> naming L become P.
Numbers are written as sdformat writes them, C++'s default six significant digits, angles as urdfdom's
Rotation::getRPY gives them; what the plugins and sensors read is that text.

Not moved, on purpose: the <gazebo reference> properties (RobotModel.gazebo_refs) stay under the link they
were written for. sdformat moves them too but applies a lumped link's mu1, mu2, laserRetro, material, ... only
to the collisions and visuals lumped in from that link (named P_fixed_joint_lump__L_...), which is what
keying them by L already says (engine/physics and urdf_assets read them so). Its link-level ones (gravity,
selfCollide, dampingFactor) would land on P; racebot applies none of them.
"""
from __future__ import annotations

import math

from racebot_sim_bridge.description.urdf_model import GazeboPlugin, UrdfJoint, Rewrite, RobotModel, SensorSpec
from racebot_sim_bridge.kinematics.rotations import Quat, as_transform, compose, rpy_to_quaternion

__all__ = ['reduce_extensions', 'reduction_order', 'urdf_rpy', 'cpp_text']

WORLD = 'world'  # sdformat never reduces a link into a parent of this name
COLLISION_SUFFIX = '_collision'
IDENTITY = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
POSED = ('sensor', 'light', 'projector')  # ReduceSDFExtensionsTransform's elements


def reduce_extensions(model: RobotModel) -> None:
    """Rewrites `model`'s plugins, sensors and gazebo_elements in place as sdformat 9 does when it lumps
    links on fixed joints; each rewritten one lists what changed in its ``rewrites``."""
    items = list(model.plugins) + list(model.sensors) + list(model.gazebo_elements)
    reduction = {}  # id(item) -> its block's reduction transform; absent: identity
    for link, joint in reduction_order(model):
        parent = joint.parent
        transform = as_transform(joint.origin_xyz + joint.origin_rpy)
        for item in items:
            if item.reference == link:
                reduction[id(item)] = transform
                _move_pose(item, transform)
                _rewrite(item, 'reference', link, parent)
                item.reference = parent
        for item in items:
            _frame_replace(item, link, parent, transform, reduction.get(id(item), IDENTITY))


def reduction_order(model: RobotModel) -> list[tuple[str, UrdfJoint]]:
    """[(link, its fixed parent joint)] in the order ReduceFixedJoints reduces them (iteratively: a long
    chain does not reach Python's recursion limit)."""
    children = {}
    for joint in sorted(model.joints.values(), key=lambda j: j.name):
        children.setdefault(joint.parent, []).append(joint)
    parent_joint = {joint.child: joint for joint in model.joints.values()}
    order = []
    stack = [(model.root_link, False)]
    while stack:
        link, fixed_done = stack.pop()
        joints = children.get(link, [])
        if not fixed_done:
            stack.append((link, True))
            stack.extend((j.child, False) for j in reversed(joints) if model.fixed_joint_reduced(j))
            continue
        joint = parent_joint.get(link)
        if joint is not None and joint.parent != WORLD and model.fixed_joint_reduced(joint):
            order.append((link, joint))
        stack.extend((j.child, False) for j in reversed(joints) if not model.fixed_joint_reduced(j))
    return order


def cpp_text(*values: float) -> str:
    """Numbers as `std::ostream << double` writes them (six significant digits), space-separated."""
    return ' '.join('%g' % v for v in values)


def urdf_rpy(q: Quat) -> tuple[float, float, float]:
    """(roll, pitch, yaw) of quaternion (x, y, z, w) as urdfdom's Rotation::getRPY gives them."""
    x, y, z, w = q
    sarg = -2.0 * (x * z - w * y)
    if sarg <= -0.99999:
        return 0.0, -math.pi / 2.0, 2.0 * math.atan2(x, -y)
    if sarg >= 0.99999:
        return 0.0, math.pi / 2.0, 2.0 * math.atan2(-x, y)
    return (math.atan2(2.0 * (y * z + w * x), w * w - x * x - y * y + z * z), math.asin(sarg),
            math.atan2(2.0 * (x * y + w * z), w * w + x * x - y * y - z * z))


def _as_written(transform):
    """The (x, y, z, roll, pitch, yaw) text sdformat writes for a transform."""
    xyz, q = transform
    return cpp_text(*(tuple(xyz) + urdf_rpy(q)))


def _rewrite(item, element, written, now):
    item.rewrites.append(Rewrite(element, written, now))


def _move_pose(item, transform):
    """ReduceSDFExtensionElementTransformReduction: the pose of a moved <sensor>, <light> or <projector>."""
    if isinstance(item, SensorSpec):
        text = _as_written(compose(transform, item.pose))
        _rewrite(item, 'pose', cpp_text(*item.pose), text)
        item.pose = tuple(float(v) for v in text.split())
        return
    if isinstance(item, GazeboPlugin) or item.element.tag not in POSED:
        return
    elem = item.element
    old = elem.find('pose')
    if old is not None and old.get('relative_to') is not None:
        return
    text = '0 0 0 0 0 0' if old is None or not (old.text or '').strip() else old.text
    if old is not None:
        elem.remove(old)
    pose = _numbers(' '.join(text.split()[:6]), 6)  # a stream read: what follows the sixth is not looked at
    if pose is None:
        return  # sdformat: "Could not parse <pose>", with the old one already removed
    new = elem.makeelement('pose', {})
    new.text = _as_written(compose(transform, pose))
    elem.append(new)
    _rewrite(item, 'pose', None if old is None else old.text, new.text)


def _numbers(text, count):
    """`count` numbers of a whitespace-separated text, or None."""
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        return None
    return values if len(values) == count and all(math.isfinite(v) for v in values) else None


def _vector3(text):
    """sdformat's ParseVector3: three numbers, else 0 0 0."""
    return _numbers(text or '', 3) or (0.0, 0.0, 0.0)


def _frame_replace(item, link, parent, transform, reduction):
    """ReduceSDFExtensionFrameReplace of one element: the names of `link` it holds become `parent`'s."""
    if isinstance(item, SensorSpec):
        collisions = item.contact_collisions
        if collisions and collisions[0] == link + COLLISION_SUFFIX:
            renamed = parent + COLLISION_SUFFIX + '_' + link
            _rewrite(item, 'contact/collision', collisions.pop(0), renamed)
            collisions.append(renamed)
        return
    if isinstance(item, GazeboPlugin):
        for tag in ('bodyName', 'frameName'):
            _plugin_frame_replace(item, tag, link, parent, transform, reduction)
        _projector_replace(item, item.params.get('projector'), link, parent)
        return
    elem = item.element
    child = elem.find('projector')
    if child is not None:
        now = _projector_replace(item, (child.text or '').strip(), link, parent)
        if now is not None:
            elem.remove(child)
            elem.append(_leaf(elem, 'projector', now))
    renamed = {'gripper': ('gripper_link', 'palm_link'), 'joint': ('parent', 'child')}.get(elem.tag, ())
    for tag in renamed:
        child = elem.find(tag)
        if child is not None and (child.text or '').strip() == link:
            elem.remove(child)
            elem.append(_leaf(elem, tag, parent))
            _rewrite(item, '%s/%s' % (elem.tag, tag), link, parent)


def _leaf(elem, tag, text):
    new = elem.makeelement(tag, {})
    new.text = text
    return new


def _projector_replace(item, text, link, parent):
    """ReduceSDFExtensionProjectorFrameReplace: 'link/name' -> 'parent/name'; the new text, or None."""
    if not text or '/' not in text:
        return None
    owner, name = text.split('/', 1)
    if owner != link:
        return None
    now = parent + '/' + name
    if isinstance(item, GazeboPlugin):
        item.params['projector'] = now
    _rewrite(item, 'projector', text, now)
    return now


def _plugin_frame_replace(plugin, tag, link, parent, transform, reduction):
    """ReduceSDFExtensionPluginFrameReplace for <tag> (bodyName or frameName) of a top-level <plugin>."""
    params = plugin.params
    if params.get(tag) != link:
        return
    params[tag] = parent
    _rewrite(plugin, tag, link, parent)
    position, rotation = reduction
    if 'xyzOffset' in params:
        position = _vector3(params['xyzOffset'])
    if 'rpyOffset' in params:
        rotation = rpy_to_quaternion(*_vector3(params['rpyOffset']))
    position, rotation = compose(transform, (position, rotation))
    for key, text in (('xyzOffset', cpp_text(*position)), ('rpyOffset', cpp_text(*urdf_rpy(rotation))),
                      ('ignition::corrected_offsets', '1')):
        _rewrite(plugin, key, params.get(key), text)
        params[key] = text

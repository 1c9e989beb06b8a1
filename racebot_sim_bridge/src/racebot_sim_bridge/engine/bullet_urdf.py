"""A URDF as PyBullet must read it, and the per-link values Gazebo keeps per collision that PyBullet keeps per link.

prepare_urdf_for_bullet rewrites a spawned robot's parsed URDF for loadURDF: Gazebo's fixed-joint lumping
(../description/urdf_lumping.py), the links in tree order (PyBullet crashes on a root written last), negligible
inertia where none is declared, each inertia as Gazebo's ODE takes it (../kinematics/inertia.py: one that is not
positive definite becomes the identity, with a warning; one PyBullet's importer would zero, though ODE takes it, is
written in its principal axes and its moments set after loading), a faceted wheel mesh replaced by the round wheel
it approximates (round_wheels.py), the Gazebo-only blocks dropped. No PyBullet calls
here: urdf_spawn.py loads the text.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import NamedTuple

from racebot_sim_bridge.description import urdf_lumping
from racebot_sim_bridge.description.urdf_model import RobotModel
from racebot_sim_bridge.engine import round_wheels
from racebot_sim_bridge.kinematics import inertia as inertia_maths
from racebot_sim_bridge.kinematics.rotations import quaternion_multiply, quaternion_to_rpy, rotate, rpy_to_quaternion

__all__ = ['NEGLIGIBLE_MASS', 'NEGLIGIBLE_INERTIA', 'BulletUrdf', 'FrictionAxes', 'WheelAxes',
           'prepare_urdf_for_bullet', 'joint_friction', 'link_friction', 'link_friction_axes', 'link_laser_retro',
           'wheel_axes']

# Mass and inertia given to links that declare no <inertial> (Gazebo drops such links' mass; PyBullet would give 1 kg).
NEGLIGIBLE_MASS = 1e-4
NEGLIGIBLE_INERTIA = 1e-9


class BulletUrdf(NamedTuple):
    """What loadURDF reads (`text`), and the principal moments to give links after it (`moments`: {link: (x, y,
    z)}), where PyBullet's importer would zero an inertia that ODE takes as it is."""
    text: str
    moments: dict


def joint_friction(urdf_model: RobotModel, joint_name: str) -> float:
    """The URDF <dynamics friction> of a joint (N*m or N), 0 without one."""
    joint = urdf_model.joints.get(joint_name)
    dynamics = getattr(joint, 'dynamics', None)
    return max(0.0, dynamics.friction) if dynamics is not None else 0.0


def link_laser_retro(urdf_model: RobotModel, link: str) -> float:
    """<laserRetro> of a (merged) PyBullet link: the first the URDF links merged into it give (Gazebo keeps it per
    collision; a ray here knows only the link it hit), 0 if none."""
    for name, spec in urdf_model.links.items():
        if urdf_model.lumped_link(name) != link or not spec.collisions:
            continue
        value = urdf_model.gazebo_refs.get(name, {}).get('laserRetro')
        if isinstance(value, float) and value:
            return value
    return 0.0


def link_friction(urdf_model: RobotModel, link: str) -> float:
    """mu of a (merged) PyBullet link: the smaller of mu1/mu2 of the URDF links merged into it that
    carry collision geometry (Gazebo keeps friction per collision; Bullet has one per link), 1 if none says."""
    mus = []
    for name, spec in urdf_model.links.items():
        if urdf_model.lumped_link(name) != link or not spec.collisions:
            continue
        props = urdf_model.gazebo_refs.get(name, {})
        values = [props[k] for k in ('mu1', 'mu2') if isinstance(props.get(k), float)]  # the reader warned of others
        if values:
            mus.append(min(values))
    return min(mus) if mus else 1.0


class FrictionAxes(NamedTuple):
    """Gazebo's anisotropic friction of a link: `mu1` along `fdir1` (a unit vector in the URDF link's frame), `mu2`
    square to it; `axle`: the link's own continuous joint's axis (unit, in its frame) when fdir1 is square to it (a
    wheel: mu1 is then the rolling direction's, whichever way the wheel has turned), else None."""
    mu1: float
    mu2: float
    fdir1: tuple
    axle: tuple | None


class WheelAxes(NamedTuple):
    """A wheel's friction pyramid as ODE builds it from <fdir1>: `mu_roll` along the rolling direction, `mu_axle`
    along the axle (each the mu1 or mu2 of whichever fdir1 lies along), `axle`: the unit axis of the wheel's
    continuous joint in its URDF link frame."""
    mu_roll: float
    mu_axle: float
    axle: tuple


def _fdir1_in_link(urdf_model: RobotModel, link: str) -> list | None:
    """A link's <fdir1> as a unit vector in its URDF frame (sdformat: in the collision's frame; the link's first
    collision's origin turns it), or None when it has none (or a zero or unreadable one)."""
    try:
        fdir1 = [float(v) for v in str(urdf_model.gazebo_refs.get(link, {}).get('fdir1', '')).split()]
    except ValueError:
        return None
    norm = sum(v * v for v in fdir1) ** 0.5 if len(fdir1) == 3 else 0.0
    if not norm > 1e-9:
        return None
    rpy = urdf_model.links[link].collisions[0].origin_rpy or (0.0, 0.0, 0.0)
    return rotate(rpy_to_quaternion(*rpy), [v / norm for v in fdir1])


def _only_link_merged(urdf_model: RobotModel, link: str) -> bool:
    """Whether `link` is the only URDF link with collisions merged into its PyBullet link (Gazebo keeps each
    collision's surface; PyBullet one per link)."""
    return [name for name, spec in urdf_model.links.items()
            if urdf_model.lumped_link(name) == link and spec.collisions] == [link]


def _continuous_axle(urdf_model: RobotModel, link: str) -> tuple | None:
    """The unit axis, in its URDF frame, of the continuous joint `link` turns on; None if it turns on none."""
    joint = urdf_model.parent_joint(link)
    if joint is None or joint.type != 'continuous' or joint.axis is None:
        return None
    norm = sum(v * v for v in joint.axis) ** 0.5
    return tuple(v / norm for v in joint.axis) if norm > 1e-9 else None


def wheel_axes(urdf_model: RobotModel, link: str) -> WheelAxes | None:
    """The WheelAxes of a link that turns on a continuous joint and whose <gazebo reference> gives an <fdir1> square
    to that joint's axis or along it (ODE then aligns the friction pyramid with the wheel: engine/wheel_friction.py),
    when it is the only URDF link with collisions merged into its PyBullet link; None otherwise. mu1 and mu2 default
    to 1, as sdformat's <friction><ode>."""
    axle = _continuous_axle(urdf_model, link)
    fdir1 = _fdir1_in_link(urdf_model, link) if axle is not None and _only_link_merged(urdf_model, link) else None
    if fdir1 is None:
        return None
    props = urdf_model.gazebo_refs.get(link, {})
    mu1, mu2 = (props[k] if isinstance(props.get(k), float) else 1.0 for k in ('mu1', 'mu2'))
    along = abs(sum(f * v for f, v in zip(fdir1, axle)))
    if along < 1e-3:
        return WheelAxes(mu1, mu2, axle)
    if along > 1.0 - 1e-6:
        return WheelAxes(mu2, mu1, axle)
    return None


def link_friction_axes(urdf_model: RobotModel, link: str) -> FrictionAxes | None:
    """The FrictionAxes of a PyBullet link whose <gazebo reference> gives mu1 and mu2 that differ and an <fdir1>
    (sdformat: in the collision's frame; the link's first collision's origin turns it into the link's), when it is
    the only URDF link with collisions merged into it; None otherwise (link_friction's smaller mu then applies)."""
    if not _only_link_merged(urdf_model, link):
        return None
    props = urdf_model.gazebo_refs.get(link, {})
    mu1, mu2 = props.get('mu1'), props.get('mu2')
    if not (isinstance(mu1, float) and isinstance(mu2, float)) or mu1 == mu2:
        return None
    fdir1 = _fdir1_in_link(urdf_model, link)
    if fdir1 is None:
        return None
    axle = _continuous_axle(urdf_model, link)
    if axle is not None and abs(sum(f * v for f, v in zip(fdir1, axle))) >= 1e-3:
        axle = None  # fdir1 is not square to it
    return FrictionAxes(mu1, mu2, tuple(fdir1), axle)


def prepare_urdf_for_bullet(root: ET.Element, urdf_model: RobotModel, visuals: bool = True, name: str = '',
                            warn: Callable[[str], None] | None = None) -> BulletUrdf:
    """The URDF text PyBullet should read, rewritten from its root element (changed in place): links
    lumped as Gazebo lumps them; negligible inertia for links that declare none; each inertia as ODE takes it
    (_inertias_as_ode_takes_them: warn(message) hears of model `name`'s that are not positive definite); a faceted
    wheel mesh made round (round_wheels.py: Bullet's rigid contacts make its facets chatter); <gazebo>,
    <transmission> and sensor blocks dropped; the visuals dropped unless `visuals`; an <axis> without xyz given
    urdfdom's default, 1 0 0 (PyBullet would read uninitialised memory for it). Mesh filenames must already be files
    PyBullet reads (urdf_assets.resolve_assets)."""
    for tag in ('gazebo', 'transmission'):
        for el in root.findall(tag):
            root.remove(el)
    for axis in root.findall('joint/axis'):
        if axis.get('xyz') is None:
            axis.set('xyz', '1 0 0')
    urdf_lumping.lump_fixed_links(root, urdf_model)
    round_wheels.round_wheel_meshes(root)
    _links_in_tree_order(root, urdf_model)
    for link in root.findall('link'):
        if link.find('inertial') is None:
            inertial = ET.SubElement(link, 'inertial')
            ET.SubElement(inertial, 'mass', value=repr(NEGLIGIBLE_MASS))
            ET.SubElement(inertial, 'inertia', ixx=repr(NEGLIGIBLE_INERTIA), iyy=repr(NEGLIGIBLE_INERTIA),
                          izz=repr(NEGLIGIBLE_INERTIA), ixy='0', ixz='0', iyz='0')
        if not visuals:
            for el in link.findall('visual'):
                link.remove(el)
    moments = _inertias_as_ode_takes_them(root, name, warn or (lambda message: None))
    _indent(root)  # PyBullet's URDF reader fails on some very long lines (a one-line document)
    return BulletUrdf(ET.tostring(root, encoding='unicode'), moments)


def _inertias_as_ode_takes_them(root: ET.Element, name: str, warn: Callable[[str], None]) -> dict:
    """Each (lumped) link's inertia rewritten so that PyBullet simulates what Gazebo's ODE does with it
    (kinematics/inertia.py): not positive definite, the identity (dBodySetMass's fallback), with one warning; positive
    definite but refused by PyBullet's importer (a moment larger than the other two together), written in its
    principal axes with placeholder moments, the real ones returned ({link: moments}) to be set after loading.
    Links without mass are left alone (a massless root is PyBullet's fixed base)."""
    moments = {}
    for link in root.findall('link'):
        inertial = link.find('inertial')
        mass, inertia = (None, None) if inertial is None else (inertial.find('mass'), inertial.find('inertia'))
        if mass is None or inertia is None or not float(mass.get('value', '0')) > 0.0:
            continue
        values = [float(inertia.get(key, '0')) for key in inertia_maths.KEYS]
        rows = inertia_maths.tensor(*values)
        if not inertia_maths.ode_positive_definite(rows):
            warn(inertia_maths.not_positive_definite(name, link.get('name'), values, float(mass.get('value'))))
            inertia.attrib.update({key: repr(v) for key, v in zip(inertia_maths.KEYS, inertia_maths.IDENTITY)})
        elif inertia_maths.bullet_importer_zeroes(rows):
            principal, rpy = inertia_maths.principal_axes(rows)
            origin = inertial.find('origin')
            if origin is None:
                origin = ET.SubElement(inertial, 'origin')
            turned = quaternion_multiply(rpy_to_quaternion(*[float(v) for v in origin.get('rpy', '0 0 0').split()]),
                                         rpy_to_quaternion(*rpy))
            origin.set('rpy', ' '.join(repr(float(v)) for v in quaternion_to_rpy(turned)))
            inertia.attrib.update({key: repr(v) for key, v in zip(inertia_maths.KEYS, inertia_maths.IDENTITY)})
            moments[link.get('name')] = principal
    return moments


def _links_in_tree_order(root: ET.Element, urdf_model: RobotModel) -> None:
    """Moves the <link> elements so that the root link comes first and every link after its parent, the
    document order kept otherwise. With URDF_MAINTAIN_LINK_ORDER PyBullet takes the links in document order
    as its multibody's: a root link written after another makes loadURDF crash the process (SIGSEGV), and a
    child written before its parent gives a body whose state turns NaN at the first step (its kinematics
    walk the links in index order, parent first). Xacros write the root `world` link last often enough."""
    links = root.findall('link')
    by_name = {link.get('name'): link for link in links}
    parent = {}  # link -> parent link, of the joints left after lumping
    for joint in root.findall('joint'):
        p, c = joint.find('parent'), joint.find('child')
        if p is not None and c is not None:
            parent[c.get('link')] = p.get('link')
    ordered, placed = [], set()
    for link in [urdf_model.root_link] + [link.get('name') for link in links]:
        chain = []
        while link in by_name and link not in placed and link not in chain:  # the reader refused cycles already
            chain.append(link)
            link = parent.get(link)
        for name in reversed(chain):
            placed.add(name)
            ordered.append(by_name[name])
    if ordered == links:
        return
    first = list(root).index(links[0])
    for link in links:
        root.remove(link)
    for offset, link in enumerate(ordered):
        root.insert(first + offset, link)


def _indent(elem: ET.Element, level: int = 0) -> None:
    """One element per line, as ET.indent (Python 3.9+) writes it; Ubuntu 20.04's Noetic runs Python 3.8."""
    pad = '\n' + '  ' * level
    children = list(elem)
    if children:
        if not (elem.text or '').strip():
            elem.text = pad + '  '
        for child in children:
            _indent(child, level + 1)
            if not (child.tail or '').strip():
                child.tail = pad + '  '
        children[-1].tail = pad if not (children[-1].tail or '').strip() else children[-1].tail

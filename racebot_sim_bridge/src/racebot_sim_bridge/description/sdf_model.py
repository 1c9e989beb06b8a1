"""An SDF 1.6 world as plain dataclasses: its physics, models (links, joints, shapes), lights.

Pure Python: no rospy, no pybullet. sdf_reader.load_world / parse_world build a World from a world file;
``physics.py`` turns it into bodies. A model with joints, plugins or sensors (``Model.is_robot``) is spawned
through the URDF path (sdf_urdf.py). Mesh shapes name only absolute files (converted by the reader), so a
World needs no search path again.

Poses are 6-tuples ``(x, y, z, roll, pitch, yaw)`` as SDF writes them; the maths on them (and their
conventions) is rotations.py's.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from racebot_sim_bridge.description.geometry import Shape
from racebot_sim_bridge.kinematics.rotations import Transform, compose

__all__ = ['World', 'Physics', 'Light', 'SdfModel', 'SdfLink', 'SdfJoint', 'Collision', 'Visual', 'ZERO_POSE',
           'UNLIMITED']

ZERO_POSE = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def _named(items, name, owner, kind):
    """The item of `items` called `name`; KeyError saying `owner` has none and naming those it has."""
    for item in items:
        if item.name == name:
            return item
    raise KeyError('%s has no %s %r (%ss: %s)' % (owner, kind, name, kind, ', '.join(i.name for i in items) or 'none'))


# ODE's friction models that Bullet has: the pyramid (friction limited in each of two directions, Gazebo's default)
# and the cone. ODE's third, box_model (a constant force limit), Bullet has not.
FRICTION_MODELS = ('pyramid_model', 'cone_model')


@dataclass
class Physics:
    """The physics block, with Gazebo's defaults."""
    type: str = 'ode'
    max_step_size: float = 0.001
    real_time_factor: float = 1.0
    real_time_update_rate: float = 1000.0
    gravity: tuple = (0.0, 0.0, -9.8)
    friction_model: str = 'pyramid_model'  # <ode><solver><friction_model>: ODE's pyramid unless cone_model
    # <ode>'s solver and constraints and <max_contacts>, by gazebo_msgs/ODEPhysics's names, with sdformat's defaults
    ode: dict = field(default_factory=lambda: dict(ODE_DEFAULTS))


# (ODEPhysics field, its path under <physics>, sdformat's default, an integer, the least value taken);
# get_physics_properties reports them, and the solver's iterations reach the engine (Bullet's constraint solver has
# no SOR, CFM or ERP of ODE's meaning). A solver that never iterates holds nothing: iters from 1.
ODE_SETTINGS = (
    ('sor_pgs_iters', 'ode/solver/iters', 50, True, 1),
    ('sor_pgs_precon_iters', 'ode/solver/precon_iters', 0, True, 0),
    ('sor_pgs_w', 'ode/solver/sor', 1.3, False, 0),
    ('cfm', 'ode/constraints/cfm', 0.0, False, 0),
    ('erp', 'ode/constraints/erp', 0.2, False, 0),
    ('contact_max_correcting_vel', 'ode/constraints/contact_max_correcting_vel', 100.0, False, 0),
    ('contact_surface_layer', 'ode/constraints/contact_surface_layer', 0.001, False, 0),
    ('max_contacts', 'max_contacts', 20, True, 0),
)
ODE_DEFAULTS = {name: default for name, _, default, _, _ in ODE_SETTINGS}


@dataclass
class Collision:
    name: str
    pose: tuple
    shape: Shape
    mu: float = None
    mu2: float = None
    laser_retro: float = 0.0  # what a laser ray that hits it reads as intensity (Gazebo's <laser_retro>)


@dataclass
class Visual:
    name: str
    pose: tuple
    shape: Shape
    rgba: tuple = None


@dataclass
class SdfLink:
    """A link.  ``mass`` is SDF's default 1.0 when no <inertial> gives one; ``inertia`` is
    ``(ixx, ixy, ixz, iyy, iyz, izz)`` about ``inertial_pose``, or None when not given. A nested model's link
    is named ``inner::link``, its ``pose`` in the outer model's frame, its ``static`` the nested model's own
    (None: the model's, as for every link of the model itself)."""
    name: str
    pose: tuple = ZERO_POSE
    mass: float = 1.0
    inertia: tuple = None
    inertial_pose: tuple = ZERO_POSE
    collisions: list = field(default_factory=list)
    visuals: list = field(default_factory=list)
    sensors: list = field(default_factory=list)  # each <sensor> element as written (XML text)
    static: bool = None

    def is_static(self, model: SdfModel) -> bool:
        """Whether the link holds still: its nested model's <static>, else `model`'s."""
        return model.static if self.static is None else self.static


# SDF's "no limit": <limit> defaults of lower/upper (+-1e16) and of effort/velocity (-1)
UNLIMITED = 1e16


@dataclass
class SdfJoint:
    """A joint.  ``pose`` is the joint frame in the child link's frame (SDF 1.6); ``axis`` is in that
    frame, or in the model's when ``axis_in_model`` (<use_parent_model_frame> or expressed_in
    __model__).  ``type`` is revolute, prismatic or fixed; limits are SDF's (``lower``/``upper`` of
    magnitude UNLIMITED and negative ``effort``/``velocity`` mean none)."""
    name: str
    type: str
    parent: str
    child: str
    pose: tuple = ZERO_POSE
    axis: tuple = (0.0, 0.0, 1.0)
    axis_in_model: bool = False
    lower: float = -UNLIMITED
    upper: float = UNLIMITED
    effort: float = -1.0
    velocity: float = -1.0
    damping: float = 0.0
    friction: float = 0.0


@dataclass
class SdfModel:
    name: str
    pose: tuple = ZERO_POSE
    static: bool = False
    links: list = field(default_factory=list)
    joints: list = field(default_factory=list)
    plugins: list = field(default_factory=list)  # each <plugin> element as written (XML text)

    @property
    def is_robot(self) -> bool:
        """Joints, plugins or sensors: what only the URDF path (sdf_urdf.py) simulates."""
        return bool(self.joints or self.plugins or any(link.sensors for link in self.links))

    def link(self, name: str) -> SdfLink:
        """The link called ``name``; KeyError naming the model's links otherwise."""
        return _named(self.links, name, 'model %r' % self.name, 'link')

    def world_pose_of(self, link: SdfLink | str, element: Collision | Visual | None = None) -> Transform:
        """World pose ``(xyz, quaternion xyzw)`` of a link, or of a collision or visual of
        it when ``element`` is given.  ``link`` is a Link or a link name."""
        if isinstance(link, str):
            link = self.link(link)
        transform = compose(self.pose, link.pose)
        if element is not None:
            transform = compose(transform, element.pose)
        return transform


@dataclass
class Light:
    """A world <light>, SDF 1.6's defaults. ``pose`` is a 6-tuple in the world; colours are rgba;
    ``attenuation``: (range, constant, linear, quadratic). Nothing is lit by it here: it is world
    state that gazebo_ros's light services read, change and delete."""
    name: str
    type: str = 'point'
    cast_shadows: bool = False
    pose: tuple = ZERO_POSE
    diffuse: tuple = (1.0, 1.0, 1.0, 1.0)
    specular: tuple = (0.1, 0.1, 0.1, 1.0)
    attenuation: tuple = (10.0, 1.0, 1.0, 0.0)
    direction: tuple = (0.0, 0.0, -1.0)


@dataclass
class WorldPlugin:
    """A world's <plugin>: loaded after its models (a compiled world plugin: gazebo_plugins/compiled_plugins.py)."""
    name: str
    filename: str
    xml: str  # the <plugin> element as written


@dataclass
class World:
    name: str = 'default'
    physics: Physics = field(default_factory=Physics)
    models: list = field(default_factory=list)
    lights: list = field(default_factory=list)
    plugins: list = field(default_factory=list)  # WorldPlugin, in the file's order
    warnings: list = field(default_factory=list)
    source: str = '<string>'

    def model(self, name: str) -> SdfModel:
        """The model called ``name``; KeyError naming the world's models otherwise."""
        return _named(self.models, name, 'world %r' % self.name, 'model')

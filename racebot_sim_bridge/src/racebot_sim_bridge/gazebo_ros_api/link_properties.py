"""gazebo_ros's link property services: get_link_properties, set_link_properties; gravity_mode false as a force.

Where PyBullet cannot do what ODE does, set_link_properties fails and says why instead of pretending: the centre
of mass cannot move and the inertia's principal axes cannot turn after a body is built (PyBullet keeps a diagonal
inertia in a fixed inertial frame); mass, principal moments and gravity_mode change for real. gravity_mode false:
the link's weight is cancelled by a force at its centre of mass before every step (cancel_gravity). As upstream,
the inertia is given in the link's axes (com.orientation is the identity).
"""
from racebot_sim_bridge.engine.physics_types import BodyKind
from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup, refused
from racebot_sim_bridge.kinematics.rotations import matrix

COM_TOLERANCE = 1e-6  # m: a centre of mass "unchanged" within this (get -> set round trips)
AXES_TOLERANCE = 1e-6  # relative size of products of inertia in the inertial frame still taken as zero
NO_LINK = '%s: link not found, did you forget to scope the link by model name?'


# -- inertia maths (pure) ---------------------------------------------------------------------------
def tensor_from_principal(diagonal, q):
    """(ixx, ixy, ixz, iyy, iyz, izz) in the link's axes of principal moments `diagonal` about axes
    turned by q: R diag R^T."""
    r = matrix(q)
    i = [[sum(r[a][k] * diagonal[k] * r[b][k] for k in range(3)) for b in range(3)] for a in range(3)]
    return i[0][0], i[0][1], i[0][2], i[1][1], i[1][2], i[2][2]


def principal_in_frame(tensor, q):
    """A link-axes tensor (ixx, ixy, ixz, iyy, iyz, izz) in the axes turned by q: R^T I R. Returns
    (diagonal, largest product of inertia relative to the largest moment)."""
    ixx, ixy, ixz, iyy, iyz, izz = tensor
    i = [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]
    r = matrix(q)
    d = [[sum(r[k][a] * i[k][m] * r[m][b] for k in range(3) for m in range(3)) for b in range(3)] for a in range(3)]
    scale = max(abs(d[0][0]), abs(d[1][1]), abs(d[2][2]), 1e-300)
    off = max(abs(d[0][1]), abs(d[0][2]), abs(d[1][2])) / scale
    return (d[0][0], d[1][1], d[2][2]), off


class LinkProperties(ServiceGroup):
    """get_link_properties and set_link_properties over a Simulator, and the step hook that cancels gravity where
    it is off."""

    SERVICES = {'get_link_properties': 'GetLinkProperties', 'set_link_properties': 'SetLinkProperties'}

    def __init__(self, rospy, sim):
        super().__init__(rospy, sim)
        self.no_gravity = {}  # (model, link) -> Model whose link has gravity_mode false

    def _link(self, name):
        """(Model, link name) of the link World::EntityByName finds under `name`; (None, None) for a
        model, a joint or nothing."""
        entity = self.entities.find_link(name)
        if entity is None:
            return None, None
        return self.sim.world.bodies[entity.model], entity.link

    def get_link_properties(self, req):
        res = self.srv.GetLinkPropertiesResponse()
        with self.sim.lock:
            body, link = self._link(req.link_name)
            if body is None:
                return refused(res, NO_LINK % 'GetLinkProperties')
            d = body.links[link].dynamics()
            res.gravity_mode = (body.name, link) not in self.no_gravity
            spec = body.source.model.link(link) if body.static and body.source.kind is BodyKind.SDF else None
        if spec is not None:  # PyBullet holds a static body with mass 0; Gazebo reports the SDF's inertial
            res.mass = spec.mass
            if spec.inertia is not None:
                res.ixx, res.ixy, res.ixz, res.iyy, res.iyz, res.izz = spec.inertia
            res.com.position.x, res.com.position.y, res.com.position.z = spec.inertial_pose[:3]
        else:
            res.mass = d.mass
            res.ixx, res.ixy, res.ixz, res.iyy, res.iyz, res.izz = tensor_from_principal(d.inertia_diagonal,
                                                                                         d.inertial_orientation)
            res.com.position.x, res.com.position.y, res.com.position.z = d.inertial_position
        res.com.orientation.w = 1.0  # as upstream: the tensor is given in the link's axes
        res.success, res.status_message = True, 'GetLinkProperties: got properties'
        return res

    def set_link_properties(self, req):
        res = self.srv.SetLinkPropertiesResponse()
        tensor = (req.ixx, req.ixy, req.ixz, req.iyy, req.iyz, req.izz)
        com = (req.com.position.x, req.com.position.y, req.com.position.z)
        with self.sim.lock:
            body, link = self._link(req.link_name)
            if body is None:
                return refused(res, NO_LINK % 'SetLinkProperties')
            if not frames.finite(req.mass, *(tensor + com)) or req.mass <= 0:
                return self.fail(res, 'SetLinkProperties: mass must be a positive number and com and inertia '
                                      'finite (got mass %r) for link [%s]' % (req.mass, req.link_name))
            if body.static:
                return self.fail(res, 'SetLinkProperties: link [%s] belongs to the static model [%s], which has '
                                      'no dynamics to change' % (req.link_name, body.name))
            d = body.links[link].dynamics()
            moved = max(abs(a - b) for a, b in zip(com, d.inertial_position))
            if moved > COM_TOLERANCE:
                return self.fail(res, 'SetLinkProperties: the centre of mass of link [%s] cannot move here '
                                      '(PyBullet fixes it when the model is built): com.position must stay '
                                      '(%g, %g, %g) as get_link_properties gives it; change the URDF\'s <inertial> '
                                      '<origin> and spawn again' % ((req.link_name,) + tuple(d.inertial_position)))
            diagonal, off = principal_in_frame(tensor, d.inertial_orientation)
            if off > AXES_TOLERANCE or min(diagonal) <= 0:
                return self.fail(res, 'SetLinkProperties: the inertia of link [%s] must have positive moments '
                                      'about the principal axes it has now (PyBullet cannot turn them): give '
                                      'a tensor with the products of inertia get_link_properties implies'
                                      % req.link_name)
            body.links[link].set_mass(req.mass, diagonal)
            if req.gravity_mode:
                self.no_gravity.pop((body.name, link), None)
            else:
                self.no_gravity[(body.name, link)] = body
                self.sim.set_step_hook('before_physics', self.cancel_gravity, True, first=True)
        res.success, res.status_message = True, 'SetLinkProperties: properties set'
        return res

    def cancel_gravity(self, _time):
        """Simulator.before_physics while some link has gravity_mode false: it gets its weight back as a force."""
        if not self.no_gravity:
            self.sim.set_step_hook('before_physics', self.cancel_gravity, False)
            return
        world = self.sim.world
        for (model, link), body in list(self.no_gravity.items()):
            if world.bodies.get(model) is not body:  # deleted (perhaps spawned again): another body
                del self.no_gravity[(model, link)]
                continue
            target = body.links[link]
            mass = target.dynamics().mass
            target.apply_wrench(tuple(-mass * g for g in world.gravity), (0.0, 0.0, 0.0),
                                accumulate=False)  # gravity off is no force in Gazebo

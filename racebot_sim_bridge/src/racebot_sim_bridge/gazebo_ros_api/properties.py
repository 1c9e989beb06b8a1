"""gazebo_ros's property services: models, joints, links, physics and lights.

get_model_properties, get_joint_properties, get_link_properties, set_link_properties,
set_joint_properties, get_physics_properties, set_physics_properties, get_light_properties,
set_light_properties, delete_light, with gazebo_ros_api_plugin's (noetic) fields, name lookups and
status messages. Where PyBullet cannot do what ODE does, the request fails and says why instead of
pretending:
- set_link_properties: the centre of mass cannot move and the inertia's principal axes cannot turn
  after a body is built (PyBullet keeps a diagonal inertia in a fixed inertial frame); mass, principal
  moments and gravity_mode change for real. gravity_mode false: the link's weight is cancelled by a
  force at its centre of mass every step;
- set_joint_properties: damping, hiStop/loStop (limits) and fmax/vel (ODE's joint motor: a velocity
  target held with at most fmax) act on the joint; erp, cfm, stop_erp, stop_cfm and fudge_factor have
  no PyBullet counterpart: accepted, logged once, reported back by nothing;
- set_physics_properties: gravity, time_step and max_update_rate change for real, and
  ode_config.sor_pgs_iters sets the solver's iterations; the other ODE numbers are kept and returned
  by get_physics_properties, without effect;
- lights are the world's (<light> and model://sun of the world file): live state (Simulator.lights, as the
  physics settings are the Simulator's and its PhysicsWorld's; the world file's description is never
  written) that these services read, change and delete. Nothing is lit by them here (the cameras do not
  shade by them).
As upstream: get_joint_properties reports every joint as REVOLUTE with no damping (its FIXME), and
the light services say nothing on success.
"""
import dataclasses
import math
import threading

from racebot_sim_bridge.engine.physics import BodyKind
from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities
from racebot_sim_bridge.kinematics.rotations import matrix, quaternion_to_rpy

# Gazebo's names for a URDF link's collisions after fixed-joint lumping (sdformat's parser_urdf).
LUMP_PREFIX = '_fixed_joint_lump__'
COLLISION_SUFFIX = '_collision'
COM_TOLERANCE = 1e-6  # m: a centre of mass "unchanged" within this (get -> set round trips)
AXES_TOLERANCE = 1e-6  # relative size of products of inertia in the inertial frame still taken as zero


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


def urdf_geom_names(model, link):
    """Gazebo's collision names of a (lumped) URDF link: its own, then those of the links merged into
    it, `L_collision`, `L_fixed_joint_lump__C_collision`, the n-th (n >= 1) with `_n` added."""
    merged = [link] + [name for name in model.links if name != link and model.lumped_link(name) == link]
    names = []
    for name in merged:
        stem = link if name == link else link + LUMP_PREFIX + name
        for _ in model.links[name].collisions:
            n = len(names)
            names.append(stem + COLLISION_SUFFIX + ('_%d' % n if n else ''))
    return names


class GazeboProperties:
    """The property services' handlers, and the step hook that cancels gravity where it is off."""

    # ODE joint parameters that PyBullet has no counterpart for.
    IGNORED_JOINT_PARAMS = ('erp', 'cfm', 'stop_erp', 'stop_cfm', 'fudge_factor')

    def __init__(self, rospy, sim):
        from gazebo_msgs import msg, srv
        self.rospy = rospy
        self.sim = sim
        self.srv = srv
        self.msg = msg
        self.ode_config = msg.ODEPhysics(auto_disable_bodies=False, sor_pgs_precon_iters=0, sor_pgs_iters=50,
                                         sor_pgs_w=1.3, sor_pgs_rms_error_tol=0.0, contact_surface_layer=0.001,
                                         contact_max_correcting_vel=100.0, cfm=0.0, erp=0.2, max_contacts=20)
        self.physics_listeners = []  # called with no arguments after set_physics_properties changed the world
        self.no_gravity = {}  # (model, link) -> Model whose link has gravity_mode false
        self.motors = {}  # (model, joint) -> (Model, vel, fmax): ODE's joint motor as set_joint_properties left it
        self._warned = set()
        self._lock = threading.Lock()
        self.entities = WorldEntities(sim.world)
        # advertised by GazeboServices, in gazebo_ros's order
        self.handlers = {
            'get_model_properties': (srv.GetModelProperties, self.get_model_properties),
            'get_joint_properties': (srv.GetJointProperties, self.get_joint_properties),
            'get_link_properties': (srv.GetLinkProperties, self.get_link_properties),
            'set_link_properties': (srv.SetLinkProperties, self.set_link_properties),
            'set_joint_properties': (srv.SetJointProperties, self.set_joint_properties),
            'get_physics_properties': (srv.GetPhysicsProperties, self.get_physics_properties),
            'set_physics_properties': (srv.SetPhysicsProperties, self.set_physics_properties),
            'get_light_properties': (srv.GetLightProperties, self.get_light_properties),
            'set_light_properties': (srv.SetLightProperties, self.set_light_properties),
            'delete_light': (srv.DeleteLight, self.delete_light),
        }

    def _fail(self, res, message):
        self.rospy.logerr(message)
        res.success, res.status_message = False, message
        return res

    # -- models and joints ------------------------------------------------------------------------
    def get_model_properties(self, req):
        res = self.srv.GetModelPropertiesResponse()
        with self.sim.lock:
            body = self.sim.world.bodies.get(req.model_name)
            if body is None:
                self.rospy.logerr('GetModelProperties: model [%s] does not exist' % req.model_name)
                res.success, res.status_message = False, 'GetModelProperties: model does not exist'
                return res
            res.body_names = WorldEntities.link_names(body)
            kind, spec = body.source.kind, body.source.model
            if kind is BodyKind.URDF:
                res.geom_names = [g for link in res.body_names for g in urdf_geom_names(spec, link)]
                # Gazebo's joints: every URDF joint not lumped away (its child stays a link of its own)
                res.joint_names = [j.name for j in spec.joints.values() if spec.lumped_link(j.child) == j.child]
            else:
                res.geom_names = [c.name for link in spec.links for c in link.collisions]
            res.is_static = bool(body.static)
        res.success, res.status_message = True, 'GetModelProperties: got properties'
        return res

    def _joint(self, name):
        """(Model, joint name) as Model::GetJoint finds it, model by model: plain or scoped name."""
        for model, body in self.sim.world.bodies.items():
            for joint in body.joints:
                if name in (joint, '%s::%s' % (model, joint)):
                    return body, joint
        return None, None

    def get_joint_properties(self, req):
        res = self.srv.GetJointPropertiesResponse()
        with self.sim.lock:
            body, joint = self._joint(req.joint_name)
            if body is None:
                res.success, res.status_message = False, 'GetJointProperties: joint not found'
                return res
            state = body.joints[joint].state()
        res.type = res.REVOLUTE  # upstream's FIXME: every joint is reported revolute, damping empty
        res.damping = []
        res.position = [state.position]
        res.rate = [state.velocity]
        res.success, res.status_message = True, 'GetJointProperties: got properties'
        return res

    def set_joint_properties(self, req):
        res = self.srv.SetJointPropertiesResponse()
        c = req.ode_joint_config
        lists = dict(damping=c.damping, hiStop=c.hiStop, loStop=c.loStop, erp=c.erp, cfm=c.cfm,
                     stop_erp=c.stop_erp, stop_cfm=c.stop_cfm, fudge_factor=c.fudge_factor, fmax=c.fmax, vel=c.vel)
        with self.sim.lock:
            body, joint = self._joint(req.joint_name)
            if body is None:
                return self._fail(res, 'SetJointProperties: joint not found')
            bad = [k for k, v in lists.items() if not frames.finite(*v)]
            if bad:
                return self._fail(res, 'SetJointProperties: %s of joint [%s] must be finite numbers'
                                  % (', '.join(bad), req.joint_name))
            first = {k: v[0] for k, v in lists.items() if len(v)}
            info = body.joints[joint]
            lower, upper = first.get('loStop', info.lower), first.get('hiStop', info.upper)
            if lower > upper:
                return self._fail(res, 'SetJointProperties: loStop %g is above hiStop %g for joint [%s]'
                                  % (lower, upper, req.joint_name))
            if first.get('damping', 0.0) < 0 or first.get('fmax', 0.0) < 0:
                return self._fail(res, 'SetJointProperties: damping and fmax of joint [%s] must be >= 0'
                                  % req.joint_name)
            extra = sorted(k for k, v in lists.items() if len(v) > 1)
            ignored = sorted(k for k in self.IGNORED_JOINT_PARAMS if k in first)
            info.set_dynamics(damping=first.get('damping'), lower=first.get('loStop'), upper=first.get('hiStop'))
            if 'fmax' in first or 'vel' in first:
                owner, vel, fmax = self.motors.get((body.name, joint), (body, 0.0, 0.0))
                if owner is not body:  # the model was deleted and spawned again: its motor starts off
                    vel, fmax = 0.0, 0.0
                vel, fmax = first.get('vel', vel), first.get('fmax', fmax)
                self.motors[(body.name, joint)] = (body, vel, fmax)
                info.drive_velocity(vel, fmax)
        for what in ([('axes beyond the first (%s): the joints here have one' % ', '.join(extra))] if extra else []) + \
                ([('%s: ODE parameters with no PyBullet counterpart' % ', '.join(ignored))] if ignored else []):
            if what not in self._warned:
                self._warned.add(what)
                self.rospy.logwarn('set_joint_properties: %s are ignored' % what)
        res.success, res.status_message = True, 'SetJointProperties: properties set'
        return res

    # -- links ------------------------------------------------------------------------------------
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
                res.success = False
                res.status_message = ('GetLinkProperties: link not found, did you forget to scope the link by '
                                      'model name?')
                return res
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
                res.success = False
                res.status_message = ('SetLinkProperties: link not found, did you forget to scope the link by '
                                      'model name?')
                return res
            if not frames.finite(req.mass, *(tensor + com)) or req.mass <= 0:
                return self._fail(res, 'SetLinkProperties: mass must be a positive number and com and inertia '
                                       'finite (got mass %r) for link [%s]' % (req.mass, req.link_name))
            if body.static:
                return self._fail(res, 'SetLinkProperties: link [%s] belongs to the static model [%s], which has '
                                       'no dynamics to change' % (req.link_name, body.name))
            d = body.links[link].dynamics()
            moved = max(abs(a - b) for a, b in zip(com, d.inertial_position))
            if moved > COM_TOLERANCE:
                return self._fail(res, 'SetLinkProperties: the centre of mass of link [%s] cannot move here '
                                       '(PyBullet fixes it when the model is built): com.position must stay '
                                       '(%g, %g, %g) as get_link_properties gives it; change the URDF\'s <inertial> '
                                       '<origin> and spawn again' % ((req.link_name,) + tuple(d.inertial_position)))
            diagonal, off = principal_in_frame(tensor, d.inertial_orientation)
            if off > AXES_TOLERANCE or min(diagonal) <= 0:
                return self._fail(res, 'SetLinkProperties: the inertia of link [%s] must have positive moments '
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

    # -- physics ----------------------------------------------------------------------------------
    def get_physics_properties(self, _req):
        res = self.srv.GetPhysicsPropertiesResponse()
        with self.sim.lock:
            res.time_step = self.sim.step_size
            res.pause = self.sim.paused
            res.max_update_rate = self.sim.real_time_update_rate
            res.gravity.x, res.gravity.y, res.gravity.z = self.sim.world.gravity
            res.ode_config = self.ode_config
        res.success, res.status_message = True, 'GetPhysicsProperties: got properties'
        return res

    def set_physics_properties(self, req):
        res = self.srv.SetPhysicsPropertiesResponse()
        g = (req.gravity.x, req.gravity.y, req.gravity.z)
        if not (math.isfinite(req.time_step) and req.time_step > 0):
            return self._fail(res, 'SetPhysicsProperties: time_step must be a positive number of seconds, got %r; '
                                   'start from what get_physics_properties gives' % req.time_step)
        if not (math.isfinite(req.max_update_rate) and req.max_update_rate >= 0):
            return self._fail(res, 'SetPhysicsProperties: max_update_rate must be >= 0 updates per second (0: as '
                                   'fast as possible), got %r' % req.max_update_rate)
        if not frames.finite(*g):
            return self._fail(res, 'SetPhysicsProperties: gravity must be finite, got (%r, %r, %r)' % g)
        o = req.ode_config
        if not frames.finite(o.sor_pgs_w, o.sor_pgs_rms_error_tol, o.contact_surface_layer,
                             o.contact_max_correcting_vel, o.cfm, o.erp):
            return self._fail(res, 'SetPhysicsProperties: ode_config values must be finite')
        with self.sim.lock:
            if req.time_step != self.sim.step_size:
                self.sim.set_step_size(req.time_step)
            self.sim.real_time_update_rate = req.max_update_rate  # the world server paces by it
            self.sim.world.set_gravity(g)
            if o.sor_pgs_iters > 0:
                self.sim.world.set_solver(numSolverIterations=int(o.sor_pgs_iters))
            self.ode_config = o
        for listener in self.physics_listeners:  # outside the lock: a listener reads the properties back
            listener()
        res.success, res.status_message = True, 'physics engine updated'
        return res

    # -- lights -----------------------------------------------------------------------------------
    def _light(self, name):
        return next((light for light in self.sim.lights if light.name == name), None)

    def get_light_properties(self, req):
        res = self.srv.GetLightPropertiesResponse()
        with self._lock:
            light = self._light(req.light_name)
            if light is None:
                res.success = False
                res.status_message = 'getLightProperties: Requested light %s not found!' % req.light_name
                return res
            res.diffuse.r, res.diffuse.g, res.diffuse.b, res.diffuse.a = light.diffuse
            _, res.attenuation_constant, res.attenuation_linear, res.attenuation_quadratic = light.attenuation
        res.success = True  # upstream leaves status_message empty
        return res

    def set_light_properties(self, req):
        res = self.srv.SetLightPropertiesResponse()
        d, s, p, q = req.diffuse, req.specular, req.pose.position, req.pose.orientation
        values = (d.r, d.g, d.b, d.a, s.r, s.g, s.b, s.a, req.attenuation_constant, req.attenuation_linear,
                  req.attenuation_quadratic, req.direction.x, req.direction.y, req.direction.z, p.x, p.y, p.z,
                  q.x, q.y, q.z, q.w)
        with self._lock:
            light = self._light(req.light_name)
            if light is None:
                res.success = False
                res.status_message = 'setLightProperties: Requested light %s not found!' % req.light_name
                return res
            if not frames.finite(*values):
                return self._fail(res, 'setLightProperties: colours, attenuation, direction and pose of light %s '
                                       'must be finite' % req.light_name)
            orientation = frames.normalised((q.x, q.y, q.z, q.w))
            index = self.sim.lights.index(light)
            self.sim.lights[index] = dataclasses.replace(
                light, cast_shadows=bool(req.cast_shadows), diffuse=(d.r, d.g, d.b, d.a),
                specular=(s.r, s.g, s.b, s.a),
                attenuation=(light.attenuation[0], req.attenuation_constant, req.attenuation_linear,
                             req.attenuation_quadratic),
                direction=(req.direction.x, req.direction.y, req.direction.z),
                pose=(p.x, p.y, p.z) + tuple(quaternion_to_rpy(orientation)))
        res.success = True  # upstream leaves status_message empty
        return res

    def delete_light(self, req):
        res = self.srv.DeleteLightResponse()
        with self._lock:
            light = self._light(req.light_name)
            if light is None:
                res.success = False
                res.status_message = 'DeleteLight: Requested light %s not found!' % req.light_name
                return res
            self.sim.lights.remove(light)
        res.success, res.status_message = True, 'DeleteLight: %s successfully deleted' % req.light_name
        return res


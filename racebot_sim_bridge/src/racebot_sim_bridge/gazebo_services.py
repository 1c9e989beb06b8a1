"""gazebo_ros's ROS API over a Simulator: the /gazebo services and the model/link state topics.

Names, request and response fields, and status messages follow gazebo_ros_api_plugin, so scripts
written against Gazebo read the same answers. Poses are those of each model's root link frame in
the world (Gazebo's model pose); link names are scoped `model::link`, fixed-joint children merged
into their parent as Gazebo merges them.
"""
import math

from gazebo_msgs import srv
from gazebo_msgs.msg import LinkState, LinkStates, ModelStates, ODEPhysics
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from std_srvs.srv import Empty, EmptyResponse

from .controller_manager import ControllerManagerServices
from .simulator import SpawnError


def to_pose(p):
    return Pose(position=Point(*p.position), orientation=Quaternion(*p.orientation))


def to_twist(t):
    return Twist(linear=Vector3(*t.linear), angular=Vector3(*t.angular))


def _finite(*values):
    return all(math.isfinite(v) for v in values)


def _normalised(q):
    n = math.sqrt(sum(c * c for c in q))
    if not math.isfinite(n) or n < 1e-9:
        return None
    return tuple(c / n for c in q)


class GazeboServices(object):
    def __init__(self, rospy, sim, ns='/gazebo'):
        self.rospy = rospy
        self.sim = sim
        self.ns = ns.rstrip('/')
        self.cm_services = {}
        self.model_states_pub = rospy.Publisher(self.ns + '/model_states', ModelStates, queue_size=1)
        self.link_states_pub = rospy.Publisher(self.ns + '/link_states', LinkStates, queue_size=1)
        s = lambda name, cls, cb: rospy.Service('%s/%s' % (self.ns, name), cls, cb)
        self.services = [
            s('spawn_urdf_model', srv.SpawnModel, self.spawn_urdf_model),
            s('spawn_sdf_model', srv.SpawnModel, self.spawn_sdf_model),
            s('delete_model', srv.DeleteModel, self.delete_model),
            s('get_model_state', srv.GetModelState, self.get_model_state),
            s('set_model_state', srv.SetModelState, self.set_model_state),
            s('get_world_properties', srv.GetWorldProperties, self.get_world_properties),
            s('get_physics_properties', srv.GetPhysicsProperties, self.get_physics_properties),
            s('get_link_state', srv.GetLinkState, self.get_link_state),
            s('set_model_configuration', srv.SetModelConfiguration, self.set_model_configuration),
            s('apply_joint_effort', srv.ApplyJointEffort, self.apply_joint_effort),
            s('pause_physics', Empty, self.pause_physics),
            s('unpause_physics', Empty, self.unpause_physics),
            s('reset_simulation', Empty, self.reset_simulation),
            s('reset_world', Empty, self.reset_world),
        ]

    def _err(self, msg):
        self.rospy.logerr(msg)
        return msg

    # -- spawn / delete ---------------------------------------------------------------------------
    def spawn_urdf_model(self, req):
        p, q = req.initial_pose.position, req.initial_pose.orientation
        orientation = _normalised((q.x, q.y, q.z, q.w)) if (q.x, q.y, q.z, q.w) != (0, 0, 0, 0) else (0, 0, 0, 1)
        if not _finite(p.x, p.y, p.z) or orientation is None:
            return srv.SpawnModelResponse(False, self._err(
                'SpawnModel: Failure - initial pose of %s is not finite or its quaternion is zero' % req.model_name))
        if req.reference_frame not in ('', 'world', 'map', '/map'):
            ref = self.sim.body(req.reference_frame.split('::')[0])
            if ref is None:
                return srv.SpawnModelResponse(False, self._err(
                    'SpawnModel: Failure - reference frame %s not found; use "world" or an existing model'
                    % req.reference_frame))
            import pybullet as pb
            rp = ref.frame_pose()
            pos, orientation = pb.multiplyTransforms(rp.position, rp.orientation, (p.x, p.y, p.z), orientation)
        else:
            pos = (p.x, p.y, p.z)
        try:
            robot = self.sim.spawn_urdf(req.model_name, req.model_xml, req.robot_namespace, pos, orientation)
        except SpawnError as err:
            return srv.SpawnModelResponse(False, self._err(str(err)))
        if robot.cm is not None:
            self.cm_services[req.model_name] = ControllerManagerServices(self.rospy, robot.cm)
            self.rospy.loginfo('%s: controller manager ready under %s/controller_manager (control period %g s, '
                               'joints: %s)' % (req.model_name, robot.ns, robot.control_period,
                                                ', '.join(robot.hw.names)))
        return srv.SpawnModelResponse(True, 'SpawnModel: Successfully spawned entity')

    def spawn_sdf_model(self, req):
        from . import sdf_world
        try:
            world = sdf_world.parse_world('<sdf version="1.6"><world name="spawn">%s</world></sdf>'
                                          % _strip_sdf_root(req.model_xml), source='spawn_sdf_model request')
        except (sdf_world.WorldError, ValueError) as err:
            return srv.SpawnModelResponse(False, self._err('SpawnModel: Failure - the SDF is not valid: %s' % err))
        for w in world.warnings:
            self.rospy.logwarn('spawn_sdf_model: %s' % w)
        if len(world.models) != 1:
            return srv.SpawnModelResponse(False, self._err(
                'SpawnModel: Failure - expected one <model> with supported geometry, found %d' % len(world.models)))
        model = world.models[0]
        model.name = req.model_name or model.name
        p = req.initial_pose.position
        q = req.initial_pose.orientation
        model.pose = _compose_pose_rpy((p.x, p.y, p.z), (q.x, q.y, q.z, q.w), model.pose)
        from .physics import PhysicsError
        with self.sim.lock:
            try:
                self.sim.world.add_sdf_model(model)
            except PhysicsError as err:
                return srv.SpawnModelResponse(False, self._err('SpawnModel: Failure - %s' % err))
        return srv.SpawnModelResponse(True, 'SpawnModel: Successfully spawned entity')

    def delete_model(self, req):
        try:
            self.sim.delete_model(req.model_name)
        except KeyError:
            return srv.DeleteModelResponse(False, self._err(
                'DeleteModel: model [%s] does not exist' % req.model_name))
        cms = self.cm_services.pop(req.model_name, None)
        if cms is not None:
            cms.shutdown()
        return srv.DeleteModelResponse(True, 'DeleteModel: successfully deleted model')

    # -- state ----------------------------------------------------------------------------------
    def get_model_state(self, req):
        res = srv.GetModelStateResponse()
        with self.sim.lock:
            body = self.sim.body(req.model_name)
            if body is None:
                res.success, res.status_message = False, 'GetModelState: model does not exist'
                return res
            pose, twist = body.frame_pose(), body.twist()
            if req.relative_entity_name not in ('', 'world', 'map', '/map'):
                ref = self.sim.body(req.relative_entity_name.split('::')[0])
                if ref is None:
                    res.success = False
                    res.status_message = 'GetModelState: reference relative_entity_name not found, did you forget ' \
                                         'to scope the body by model name?'
                    return res
                pose, twist = _relative(pose, twist, ref.frame_pose(), ref.twist())
            res.header.stamp = self.rospy.Time.from_sec(self.sim.time)
            res.header.frame_id = req.relative_entity_name
        res.pose, res.twist = to_pose(pose), to_twist(twist)
        res.success, res.status_message = True, 'GetModelState: got properties'
        return res

    def set_model_state(self, req):
        st = req.model_state
        p, q = st.pose.position, st.pose.orientation
        orn = _normalised((q.x, q.y, q.z, q.w))
        lin, ang = st.twist.linear, st.twist.angular
        if orn is None or not _finite(p.x, p.y, p.z, lin.x, lin.y, lin.z, ang.x, ang.y, ang.z):
            return srv.SetModelStateResponse(False, self._err(
                'SetModelState: pose or twist of %s is not finite, or its quaternion is zero' % st.model_name))
        with self.sim.lock:
            body = self.sim.body(st.model_name)
            if body is None:
                return srv.SetModelStateResponse(False, self._err(
                    'Updating ModelState: model [%s] does not exist' % st.model_name))
            if body.static:
                return srv.SetModelStateResponse(False, self._err(
                    'SetModelState: model [%s] is static and cannot be moved here' % st.model_name))
            com = body.com_pose_for_frame((p.x, p.y, p.z), orn)
            self.sim.world.set_pose(body, com.position, com.orientation, (lin.x, lin.y, lin.z), (ang.x, ang.y, ang.z))
        return srv.SetModelStateResponse(True, 'SetModelState: set model state done')

    def get_world_properties(self, _req):
        res = srv.GetWorldPropertiesResponse()
        res.sim_time = self.sim.time
        res.model_names = self.sim.model_names()
        res.rendering_enabled = bool(self.sim.rendering)
        res.success, res.status_message = True, 'GetWorldProperties: got properties'
        return res

    def get_physics_properties(self, _req):
        ph = self.sim.spec.physics
        res = srv.GetPhysicsPropertiesResponse()
        res.time_step = self.sim.step_size
        res.pause = self.sim.paused
        res.max_update_rate = ph.real_time_update_rate
        res.gravity = Vector3(*self.sim.world.gravity)
        res.ode_config = ODEPhysics(auto_disable_bodies=False, sor_pgs_precon_iters=0, sor_pgs_iters=50,
                                    sor_pgs_w=1.3, sor_pgs_rms_error_tol=0.0, contact_surface_layer=0.001,
                                    contact_max_correcting_vel=100.0, cfm=0.0, erp=0.2, max_contacts=20)
        res.success, res.status_message = True, 'GetPhysicsProperties: got properties'
        return res

    def _find_link(self, scoped):
        model, _, link = scoped.rpartition('::')
        with self.sim.lock:
            if model:
                body = self.sim.body(model)
                return (body, link) if body is not None and link in body.link_index else (None, None)
            for body in self.sim.world.bodies.values():
                if link in body.link_index:
                    return body, link
        return None, None

    def get_link_state(self, req):
        res = srv.GetLinkStateResponse()
        body, link = self._find_link(req.link_name)
        if body is None:
            res.success = False
            res.status_message = 'GetLinkState: link not found'
            return res
        with self.sim.lock:
            pose, twist = self.sim.world.link_state(body, link)
            if req.reference_frame not in ('', 'world', 'map', '/map'):
                rbody, rlink = self._find_link(req.reference_frame)
                if rbody is None:
                    res.success = False
                    res.status_message = 'GetLinkState: reference frame not found, did you forget to scope the link ' \
                                         'by model name?'
                    return res
                rpose, rtwist = self.sim.world.link_state(rbody, rlink)
                pose, twist = _relative(pose, twist, rpose, rtwist)
        res.link_state = LinkState(link_name=req.link_name, pose=to_pose(pose), twist=to_twist(twist),
                                   reference_frame=req.reference_frame)
        res.success, res.status_message = True, 'GetLinkState: got state'
        return res

    def set_model_configuration(self, req):
        if len(req.joint_names) != len(req.joint_positions):
            return srv.SetModelConfigurationResponse(False, self._err(
                'SetModelConfiguration: joint_names and joint_positions have different lengths (%d, %d)'
                % (len(req.joint_names), len(req.joint_positions))))
        with self.sim.lock:
            body = self.sim.body(req.model_name)
            if body is None:
                return srv.SetModelConfigurationResponse(False, self._err(
                    'SetModelConfiguration: model [%s] does not exist' % req.model_name))
            unknown = [j for j in req.joint_names if j not in body.joints]
            if unknown or not _finite(*req.joint_positions):
                return srv.SetModelConfigurationResponse(False, self._err(
                    'SetModelConfiguration: %s of model [%s] (movable joints: %s)' % (
                        'unknown joints %s' % unknown if unknown else 'positions must be finite', req.model_name,
                        ', '.join(sorted(body.joints)))))
            for j, pos in zip(req.joint_names, req.joint_positions):
                self.sim.world.set_joint_position(body, j, pos)
            robot = self.sim.robots.get(req.model_name)
            if robot is not None:
                robot.reset_joint_readings(self.sim.world)
        return srv.SetModelConfigurationResponse(True, 'SetModelConfiguration: success')

    def apply_joint_effort(self, req):
        with self.sim.lock:
            for body in self.sim.world.bodies.values():
                if req.joint_name in body.joints:
                    break
            else:
                return srv.ApplyJointEffortResponse(False, self._err(
                    'ApplyJointEffort: joint [%s] not found' % req.joint_name))
            if not math.isfinite(req.effort):
                return srv.ApplyJointEffortResponse(False, self._err('ApplyJointEffort: effort must be finite'))
            start = max(req.start_time.to_sec(), self.sim.time)
            duration = req.duration.to_sec()
            end = math.inf if duration < 0 else start + duration
            self.sim.add_timed_effort(body, req.joint_name, req.effort, start, end)
        return srv.ApplyJointEffortResponse(True, '')

    # -- physics control ------------------------------------------------------------------------
    def pause_physics(self, _req):
        self.sim.paused = True
        return EmptyResponse()

    def unpause_physics(self, _req):
        self.sim.paused = False
        return EmptyResponse()

    def reset_simulation(self, _req):
        self.sim.reset_simulation()
        return EmptyResponse()

    def reset_world(self, _req):
        self.sim.reset_world()
        return EmptyResponse()

    # -- topics ---------------------------------------------------------------------------------
    def publish_states(self):
        """model_states and link_states, each only when somebody listens."""
        want_models = self.model_states_pub.get_num_connections() > 0
        want_links = self.link_states_pub.get_num_connections() > 0
        if not (want_models or want_links):
            return
        with self.sim.lock:
            models, links = ModelStates(), LinkStates()
            for name, body in self.sim.world.bodies.items():
                if want_models:
                    models.name.append(name)
                    models.pose.append(to_pose(body.frame_pose()))
                    models.twist.append(to_twist(body.twist()))
                if want_links:
                    for link in body.link_names():
                        pose, twist = self.sim.world.link_state(body, link)
                        links.name.append('%s::%s' % (name, link))
                        links.pose.append(to_pose(pose))
                        links.twist.append(to_twist(twist))
        if want_models:
            self.model_states_pub.publish(models)
        if want_links:
            self.link_states_pub.publish(links)

    def shutdown(self):
        for s in self.services:
            s.shutdown()
        for c in self.cm_services.values():
            c.shutdown()


def _relative(pose, twist, ref_pose, ref_twist):
    """pose and twist expressed in the frame of a reference pose (twist as a difference, rotated)."""
    import pybullet as pb
    inv_p, inv_o = pb.invertTransform(ref_pose.position, ref_pose.orientation)
    p, o = pb.multiplyTransforms(inv_p, inv_o, pose.position, pose.orientation)
    rot = pb.getMatrixFromQuaternion(inv_o)

    def rotate(v):
        return tuple(rot[3 * i] * v[0] + rot[3 * i + 1] * v[1] + rot[3 * i + 2] * v[2] for i in range(3))
    lin = rotate([a - b for a, b in zip(twist.linear, ref_twist.linear)])
    ang = rotate([a - b for a, b in zip(twist.angular, ref_twist.angular)])
    from .physics import Pose as P, Twist as T
    return P(tuple(p), tuple(o)), T(lin, ang)


def _strip_sdf_root(xml):
    """The <model> element(s) of an SDF document given to spawn_sdf_model."""
    import xml.etree.ElementTree as ET
    root = ET.fromstring(xml)
    models = [root] if root.tag == 'model' else root.findall('model')
    return ''.join(ET.tostring(m, encoding='unicode') for m in models)


def _compose_pose_rpy(position, quat, rel):
    """A spawn pose (xyz + quaternion) composed with a model's own SDF pose (x, y, z, r, p, y)."""
    import pybullet as pb
    q = _normalised(quat) or (0, 0, 0, 1)
    p, o = pb.multiplyTransforms(position, q, rel[:3], pb.getQuaternionFromEuler(rel[3:]))
    r = pb.getEulerFromQuaternion(o)
    return tuple(p) + tuple(r)

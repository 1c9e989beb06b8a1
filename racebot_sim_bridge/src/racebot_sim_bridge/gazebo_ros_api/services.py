"""gazebo_ros's ROS API over a Simulator: the /gazebo services and the model/link state topics.

Names, request and response fields, and status messages follow gazebo_ros_api_plugin, so scripts
written against Gazebo read the same answers. Poses are those of each model's frame in the world
(Gazebo's model pose); link names are scoped `model::link`, fixed-joint children merged into their
parent as Gazebo merges them. Names of models, links and reference frames are found as Gazebo's
World::EntityByName finds them (frames.resolve); '', 'world', 'map' and '/map' are the world.
Where upstream has no check (non-finite numbers, an empty model name) the answer is ours and says
what to change. A spawn request's XML is parsed once; the tree and the model read from it go on to the
Simulator (a robot's controller manager services are gazebo_ros_control's, offered by its plugin).
"""

from gazebo_msgs import srv
from gazebo_msgs.msg import LinkState, LinkStates, ModelState, ModelStates
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from std_srvs.srv import Empty, EmptyResponse

import xml.etree.ElementTree as ET

from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.description import model_path, sdf_reader, spawn_xml, urdf_model, urdf_reader
from racebot_sim_bridge.engine.physics import PhysicsError
from racebot_sim_bridge.gazebo_ros_api.forces import GazeboForces
from racebot_sim_bridge.gazebo_ros_api.properties import GazeboProperties
from racebot_sim_bridge.kinematics.rotations import as_transform, as_xyz_rpy
from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.engine.simulator import SpawnError
from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities

# gazebo_ros_api_plugin's status messages, word for word.
SPAWN_OK = 'SpawnModel: Successfully spawned entity'
SPAWN_INVALID_URDF = 'SpawnModel: Failure - entity format is invalid.'
SPAWN_NOT_SDF_OR_URDF = ('GazeboRosApiPlugin SpawnModel Failure: input model_xml not SDF or URDF, or cannot be '
                         'converted to Gazebo compatible format.')
SPAWN_EXISTS = 'SpawnModel: Failure - entity already exists.'
SPAWN_NO_FRAME = 'SpawnModel: reference reference_frame not found, did you forget to scope the link by model name?'
SPAWN_NO_PACKAGE = 'urdf reference package name does not exist: '
SPAWN_NOT_LOADED = ('SpawnModel: Entity pushed to spawn queue, but spawn service timed out waiting for entity to '
                    'appear in simulation under the name %s')


def _pose_msg(pose):
    """geometry_msgs/Pose of a (position, quaternion xyzw) pair."""
    return Pose(position=Point(*pose[0]), orientation=Quaternion(*pose[1]))


def _twist_msg(twist):
    """geometry_msgs/Twist of a (linear, angular) pair."""
    return Twist(linear=Vector3(*twist[0]), angular=Vector3(*twist[1]))


def _pose_in(msg):
    """(position, unit quaternion) of a geometry_msgs/Pose, a zero quaternion read as the identity
    (as ignition's Normalize makes it); None if a number is not finite."""
    p, q = msg.position, msg.orientation
    orientation = frames.normalised((q.x, q.y, q.z, q.w))
    if orientation is None or not frames.finite(p.x, p.y, p.z):
        return None
    return (p.x, p.y, p.z), orientation


def _twist_in(msg):
    """(linear, angular) of a geometry_msgs/Twist; None if a number is not finite."""
    lin, ang = (msg.linear.x, msg.linear.y, msg.linear.z), (msg.angular.x, msg.angular.y, msg.angular.z)
    return (lin, ang) if frames.finite(*lin + ang) else None


# The order of gazebo_ros_api_plugin.cpp's advertiseServices(): a client that waits for one service finds
# those before it (registering takes a master call each; reset_world, the last, means all are there)
ADVERTISED = (
    'spawn_sdf_model', 'spawn_urdf_model', 'delete_model', 'delete_light', 'get_model_properties',
    'get_model_state', 'get_world_properties', 'get_joint_properties', 'get_link_properties', 'get_link_state',
    'get_light_properties', 'set_light_properties', 'get_physics_properties', 'set_link_properties',
    'set_physics_properties', 'set_model_state', 'set_model_configuration', 'set_joint_properties',
    'set_link_state', 'pause_physics', 'unpause_physics', 'apply_body_wrench', 'apply_joint_effort',
    'clear_joint_forces', 'clear_body_wrenches', 'reset_simulation', 'reset_world',
)


class GazeboServices:
    def __init__(self, rospy, sim, ns='/gazebo'):
        self.rospy = rospy
        self.sim = sim
        self.ns = ns.rstrip('/')
        self.entities = WorldEntities(sim.world)
        self.model_states_pub = rospy.Publisher(self.ns + '/model_states', ModelStates, queue_size=1)
        self.link_states_pub = rospy.Publisher(self.ns + '/link_states', LinkStates, queue_size=1)
        # properties, physics settings and lights; wrenches and joint efforts: modules of their own
        self.properties = GazeboProperties(rospy, sim)
        self.forces = GazeboForces(rospy, sim)
        handlers = {
            'spawn_urdf_model': (srv.SpawnModel, self.spawn_urdf_model),
            'spawn_sdf_model': (srv.SpawnModel, self.spawn_sdf_model),
            'delete_model': (srv.DeleteModel, self.delete_model),
            'get_model_state': (srv.GetModelState, self.get_model_state),
            'set_model_state': (srv.SetModelState, self.set_model_state),
            'get_world_properties': (srv.GetWorldProperties, self.get_world_properties),
            'get_link_state': (srv.GetLinkState, self.get_link_state),
            'set_link_state': (srv.SetLinkState, self.set_link_state),
            'set_model_configuration': (srv.SetModelConfiguration, self.set_model_configuration),
            'pause_physics': (Empty, self.pause_physics),
            'unpause_physics': (Empty, self.unpause_physics),
            'reset_simulation': (Empty, self.reset_simulation),
            'reset_world': (Empty, self.reset_world),
            **self.properties.handlers, **self.forces.handlers,
        }
        self.services = [rospy.Service('%s/%s' % (self.ns, name), *handlers[name]) for name in ADVERTISED]
        # the topic forms of set_model_state / set_link_state: the same handlers, answers only logged
        self.subscribers = [
            rospy.Subscriber(self.ns + '/set_model_state', ModelState,
                             lambda m: self.set_model_state(srv.SetModelStateRequest(model_state=m)), queue_size=10),
            rospy.Subscriber(self.ns + '/set_link_state', LinkState,
                             lambda m: self.set_link_state(srv.SetLinkStateRequest(link_state=m)), queue_size=10),
        ]

    def _err(self, msg):
        self.rospy.logerr(msg)
        return msg

    # -- spawn / delete ---------------------------------------------------------------------------
    def spawn_urdf_model(self, req):
        return self._answered(req, self._spawn_urdf_model)

    def spawn_sdf_model(self, req):
        return self._answered(req, lambda r: self._spawn(r, spawn_xml.parse(r.model_xml)))

    def _answered(self, req, spawn):
        """spawn(req)'s response; for an error nothing foresaw, a refusal saying what it was (rospy would answer
        the client a bare error). The Simulator and PhysicsWorld take out what a failed spawn made."""
        try:
            return spawn(req)
        except Exception as err:
            return self._not_loaded(req.model_name, 'the model could not be spawned (%s: %s)'
                                    % (type(err).__name__, err))

    def _spawn_urdf_model(self, req):
        root = spawn_xml.parse(req.model_xml)
        if not spawn_xml.is_urdf(root):
            # upstream also fails the call itself (returns false); rospy cannot send a response with that
            return srv.SpawnModelResponse(False, self._err('%s %s' % (SPAWN_INVALID_URDF, spawn_xml.format_problem(
                req.model_xml, root, 'a URDF has <robot> (for SDF, call spawn_sdf_model)'))))
        for package in spawn_xml.referenced_packages(req.model_xml):  # upstream checks these before all else
            if model_path.package_dir(package) is None:
                self.rospy.logerr("SpawnModel: %s names package://%s/..., and '%s' is not on the ROS package path; "
                                  "source its workspace's setup.bash (or spawn_model -package_to_model for "
                                  "model:// URIs)" % (req.model_name, package, package))
                return srv.SpawnModelResponse(False, SPAWN_NO_PACKAGE + package)  # upstream also fails the call
        return self._spawn(req, root)

    def _spawn(self, req, root):
        """spawnSDFModel's order: reference frame, format, name in use, then the spawn itself. `root`: the
        request's XML as parsed (None when it is not XML)."""
        name = req.model_name
        pose = _pose_in(req.initial_pose)
        if pose is None:
            return srv.SpawnModelResponse(False, self._err(
                'SpawnModel: Failure - initial_pose of %s is not finite; give finite numbers' % name))
        with self.sim.lock:
            frame = self._frame_pose(req.reference_frame)
            if frame is False:
                return srv.SpawnModelResponse(False, SPAWN_NO_FRAME)
            if frame is not None:
                pose = frames.in_world(frame, pose)
            if spawn_xml.is_sdf(root):
                spawn = self._spawn_sdf
            elif spawn_xml.is_urdf(root):
                spawn = self._spawn_urdf
            else:
                problem = spawn_xml.format_problem(req.model_xml, root, 'SDF has <sdf> (or <gazebo>), URDF <robot>')
                return srv.SpawnModelResponse(False, self._err('%s %s' % (SPAWN_NOT_SDF_OR_URDF, problem)))
            if name and name in self.sim.world.bodies:
                self.rospy.logerr('SpawnModel: Failure - model name %s already exist. Delete it first (rosservice '
                                  'call %s/delete_model %s) or spawn with another -model name' % (name, self.ns, name))
                return srv.SpawnModelResponse(False, SPAWN_EXISTS)
            return spawn(req, root, pose)

    def _spawn_urdf(self, req, root, pose):
        name = req.model_name
        try:
            model = urdf_reader.parse_urdf(root)
        except urdf_model.UrdfError as err:
            # Gazebo cannot load it and the service waits out its 10 s; upstream's words, then the reason
            return self._not_loaded(name, 'the URDF is not valid: %s' % err)
        return self._spawned(lambda: self.sim.spawn_urdf(name, root, req.robot_namespace, pose[0], pose[1],
                                                         model=model))

    def _spawned(self, spawn):
        """The response to a spawn through the URDF path."""
        try:
            spawn()
        except SpawnError as err:
            return srv.SpawnModelResponse(False, self._err(str(err)))
        return srv.SpawnModelResponse(True, SPAWN_OK)

    def _not_loaded(self, name, reason):
        """The answer to a spawn whose model did not appear: upstream's status words, then why."""
        return srv.SpawnModelResponse(False, self._err('%s: %s' % (SPAWN_NOT_LOADED % name, reason)))

    def _spawn_sdf(self, req, root, pose):
        spawn_xml.add_robot_namespace(root, req.robot_namespace)
        document = ET.Element('sdf', version='1.6')
        ET.SubElement(document, 'world', name='spawn').extend(_sdf_models(root))
        try:
            world = sdf_reader.parse_world(document, source='spawn_sdf_model request')
        except (sdf_reader.WorldError, ValueError) as err:
            return self._not_loaded(req.model_name, 'the SDF is not valid: %s' % err)
        for w in world.warnings:
            self.rospy.logwarn('spawn_sdf_model: %s' % w)
        if len(world.models) != 1:
            return self._not_loaded(req.model_name, 'the SDF must hold one <model> with supported geometry, found %d'
                                    % len(world.models))
        model = world.models[0]
        model.name = req.model_name or model.name
        if model.name in self.sim.world.bodies:
            self.rospy.logerr('SpawnModel: Failure - model name %s already exist.' % model.name)
            return srv.SpawnModelResponse(False, SPAWN_EXISTS)
        # the request's pose, then the model's own <pose> in it (updateSDFAttributes)
        model.pose = as_xyz_rpy(frames.in_world(pose, as_transform(model.pose)))
        if model.is_robot:  # joints, plugins or sensors: the URDF path simulates them
            return self._spawned(lambda: self.sim.spawn_sdf_robot(model, req.robot_namespace))
        try:
            self.sim.world.add_sdf_model(model)
        except PhysicsError as err:
            return self._not_loaded(model.name, str(err))
        return srv.SpawnModelResponse(True, SPAWN_OK)

    def delete_model(self, req):
        try:
            self.sim.delete_model(req.model_name)
        except KeyError:
            self.rospy.logerr('DeleteModel: model [%s] does not exist' % req.model_name)
            return srv.DeleteModelResponse(False, 'DeleteModel: model does not exist')
        return srv.DeleteModelResponse(True, 'DeleteModel: successfully deleted model')

    # -- state ----------------------------------------------------------------------------------
    def _frame_pose(self, name):
        """World pose of the entity (model or link) called `name`; None for the world's names; False
        when nothing has that name. Caller holds the lock."""
        return self._frame_state(name)[0]

    def _frame_state(self, name):
        entity = self.entities.resolve(name)
        if entity is not None:
            return self.entities.state(entity)
        return (None, None) if frames.is_world_frame(name) else (False, None)

    def _model(self, name):
        """The physics.Model of the model called `name` (World::ModelByName: a link's name is no model)."""
        entity = self.entities.resolve(name)
        return self.sim.world.bodies[entity.model] if entity is not None and entity.link is None else None

    def get_model_state(self, req):
        res = srv.GetModelStateResponse()
        with self.sim.lock:
            body = self._model(req.model_name)
            if body is None:
                self.rospy.logerr('GetModelState: model [%s] does not exist' % req.model_name)
                res.success, res.status_message = False, 'GetModelState: model does not exist'
                return res
            # header.seq: rospy numbers every response itself (upstream counts calls per model)
            res.header.stamp = ros_time(self.rospy.Time, self.sim.time)
            res.header.frame_id = req.relative_entity_name
            pose, twist = self.entities.model_state(body)
            frame, frame_twist = self._frame_state(req.relative_entity_name)
            if frame is False:
                res.success = False
                res.status_message = 'GetModelState: reference relative_entity_name not found, did you forget ' \
                                     'to scope the body by model name?'
                return res
            if frame is not None:
                pose = frames.relative_to(frame, pose)
                twist = frames.twist_seen_from(frame, frame_twist, twist)
        res.pose, res.twist = _pose_msg(pose), _twist_msg(twist)
        res.success, res.status_message = True, 'GetModelState: got properties'
        return res

    def set_model_state(self, req):
        st = req.model_state
        with self.sim.lock:
            body = self._model(st.model_name)
            if body is None:
                self.rospy.logerr('Updating ModelState: model [%s] does not exist' % st.model_name)
                return srv.SetModelStateResponse(False, 'SetModelState: model does not exist')
            frame = self._frame_pose(st.reference_frame)
            if frame is False:
                self.rospy.logerr('Updating ModelState: for model[%s], specified reference frame entity [%s] does '
                                  'not exist' % (st.model_name, st.reference_frame))
                return srv.SetModelStateResponse(False, 'SetModelState: specified reference frame entity does not '
                                                        'exist')
            pose, twist = _pose_in(st.pose), _twist_in(st.twist)
            if pose is None or twist is None:
                return srv.SetModelStateResponse(False, self._err(
                    'SetModelState: Failure - the %s of model [%s] is not finite; give finite numbers'
                    % ('pose' if pose is None else 'twist', st.model_name)))
            if frame is not None:
                pose = frames.in_world(frame, pose)
                twist = frames.set_model_twist(frame, twist)
            self.entities.set_model_state(body, pose, twist)
        return srv.SetModelStateResponse(True, 'SetModelState: set model state done')

    def get_world_properties(self, _req):
        res = srv.GetWorldPropertiesResponse()
        res.sim_time = self.sim.time
        res.model_names = self.sim.model_names()
        res.rendering_enabled = True  # gazebo_ros answers true whether or not a window renders
        res.success, res.status_message = True, 'GetWorldProperties: got properties'
        return res

    def get_link_state(self, req):
        res = srv.GetLinkStateResponse()
        with self.sim.lock:
            link = self.entities.find_link(req.link_name)
            if link is None:
                res.success = False
                res.status_message = 'GetLinkState: link not found, did you forget to scope the link by model name?'
                return res
            pose, twist = self.entities.state(link)
            frame, frame_twist = self._frame_state(req.reference_frame)
            if frame is False:
                res.success = False
                res.status_message = 'GetLinkState: reference reference_frame not found, did you forget to scope ' \
                                     'the link by model name?'
                return res
            if frame is not None:
                pose = frames.relative_to(frame, pose)
                twist = frames.twist_seen_from(frame, frame_twist, twist)
        res.link_state = LinkState(link_name=req.link_name, pose=_pose_msg(pose), twist=_twist_msg(twist),
                                   reference_frame=req.reference_frame)
        res.success, res.status_message = True, 'GetLinkState: got state'
        return res

    def set_link_state(self, req):
        st = req.link_state
        with self.sim.lock:
            link = self.entities.find_link(st.link_name)
            if link is None:
                self.rospy.logerr('Updating LinkState: link [%s] does not exist' % st.link_name)
                return srv.SetLinkStateResponse(False, 'SetLinkState: link does not exist')
            # Gazebo 8+ takes only a link as the reference here (a model's name is refused)
            frame = self.entities.find_link(st.reference_frame)
            if frame is None and not frames.is_world_frame(st.reference_frame):
                self.rospy.logerr('Updating LinkState: reference_frame is not a valid entity name')
                return srv.SetLinkStateResponse(False, 'SetLinkState: failed')
            pose, twist = _pose_in(st.pose), _twist_in(st.twist)
            if pose is None or twist is None:
                return srv.SetLinkStateResponse(False, self._err(
                    'SetLinkState: Failure - the %s of link [%s] is not finite; give finite numbers'
                    % ('pose' if pose is None else 'twist', st.link_name)))
            if frame is not None:
                frame_pose, frame_twist = self.entities.state(frame)
                pose = frames.in_world(frame_pose, pose)
                twist = frames.set_link_twist(frame_twist, twist)
            self.entities.set_link_state(self.sim.world.bodies[link.model], link.link, pose, twist)
        return srv.SetLinkStateResponse(True, 'SetLinkState: success')

    def set_model_configuration(self, req):
        with self.sim.lock:
            body = self._model(req.model_name)
            if body is None:
                self.rospy.logerr('SetModelConfiguration: model [%s] does not exist' % req.model_name)
                return srv.SetModelConfigurationResponse(False, 'SetModelConfiguration: model does not exist')
            if len(req.joint_names) != len(req.joint_positions):
                return srv.SetModelConfigurationResponse(
                    False, 'SetModelConfiguration: joint name and position list have different lengths')
            if not frames.finite(*req.joint_positions):
                return srv.SetModelConfigurationResponse(False, self._err(
                    'SetModelConfiguration: Failure - joint positions of model [%s] must be finite, got %s'
                    % (req.model_name, list(req.joint_positions))))
            # Gazebo's JointController: each joint of the model takes its plain or scoped name's
            # position; names that are no joint of the model are passed over.
            wanted = dict(zip(req.joint_names, req.joint_positions))
            used = set()
            for joint in body.joints:
                for key in (joint, '%s::%s' % (req.model_name, joint)):
                    if key in wanted:
                        body.joints[joint].set_position(wanted[key])
                        used.add(key)
                        break
            unknown = [n for n in wanted if n not in used]
            if unknown:
                self.rospy.logwarn('SetModelConfiguration: %s not movable joints of model [%s]; ignored, as Gazebo '
                                   'does (its movable joints: %s)' % (unknown, req.model_name,
                                                                     ', '.join(body.joints) or 'none'))
            robot = self.sim.robots.get(req.model_name)
            if robot is not None and robot.control is not None:
                robot.control.reset_joint_readings(self.sim.world)
        return srv.SetModelConfigurationResponse(True, 'SetModelConfiguration: success')

    # -- physics control ------------------------------------------------------------------------
    def pause_physics(self, _req):
        self.sim.set_paused(True)
        return EmptyResponse()

    def unpause_physics(self, _req):
        self.sim.set_paused(False)
        return EmptyResponse()

    def reset_simulation(self, _req):
        self.sim.reset_simulation()
        return EmptyResponse()

    def reset_world(self, _req):
        self.sim.reset_world()
        return EmptyResponse()

    # -- topics ---------------------------------------------------------------------------------
    def states_wanted(self):
        """Whether somebody listens to model_states or link_states."""
        return self.model_states_pub.get_num_connections() > 0 or self.link_states_pub.get_num_connections() > 0

    def publish_states(self):
        """model_states and link_states, each only when somebody listens."""
        want_models = self.model_states_pub.get_num_connections() > 0
        want_links = self.link_states_pub.get_num_connections() > 0
        if not (want_models or want_links):
            return
        models, links = self.states(want_models, want_links)
        if want_models:
            self.model_states_pub.publish(models)
        if want_links:
            self.link_states_pub.publish(links)

    def states(self, want_models=True, want_links=True):
        """(ModelStates, LinkStates) of the world now, each left empty unless wanted. A nested model's links are
        links of its outer model: outer::inner::link."""
        with self.sim.lock:
            models, links = ModelStates(), LinkStates()
            for name, body in self.sim.world.bodies.items():
                if want_models:
                    pose, twist = self.entities.model_state(body)
                    models.name.append(name)
                    models.pose.append(_pose_msg(pose))
                    models.twist.append(_twist_msg(twist))
                if want_links:
                    for link in self.entities.link_names(body):
                        pose, twist = self.entities.link_state(body, link)
                        links.name.append('%s::%s' % (name, link))
                        links.pose.append(_pose_msg(pose))
                        links.twist.append(_twist_msg(twist))
        return models, links

    def shutdown(self):
        for s in self.services:
            s.shutdown()
        for sub in self.subscribers:
            sub.unregister()


def _sdf_models(root):
    """The <model> element(s) of an SDF document given to spawn_sdf_model (its parsed root); without one,
    the first <include> of its <world> (spawn_model -database sends <world><include><uri>model://NAME</uri>
    ...), as gazebo_ros's updateSDFAttributes reads it."""
    models = [root] if root.tag == 'model' else root.findall('model')
    if not models and root.find('world') is not None:
        models = root.find('world').findall('include')[:1]
    return models


"""gazebo_ros's spawn and delete services: spawn_urdf_model, spawn_sdf_model, delete_model.

As gazebo_ros_api_plugin (noetic) answers them, status messages word for word. A spawn request's XML is parsed
once (spawn_xml); the tree and the model read from it go on to the Simulator: a URDF (and an SDF robot: joints,
plugins or sensors) through its URDF path, an SDF model without them as bodies of its own. The request's pose is
its initial_pose in the reference_frame's entity (frames.resolve finds it). Where upstream has no check
(non-finite numbers) the answer is ours and says what to change; an error nothing foresaw is a refusal that says
what it was, not a bare service error.
"""
import xml.etree.ElementTree as ET

from gazebo_msgs import srv

from racebot_sim_bridge.description import model_path, sdf_reader, spawn_xml, urdf_model, urdf_reader
from racebot_sim_bridge.engine.physics_types import PhysicsError
from racebot_sim_bridge.engine.simulator import SpawnError
from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup
from racebot_sim_bridge.kinematics.rotations import as_transform, as_xyz_rpy

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


def _sdf_models(root):
    """The <model> element(s) of an SDF document given to spawn_sdf_model (its parsed root); without one,
    the first <include> of its <world> (spawn_model -database sends <world><include><uri>model://NAME</uri>
    ...), as gazebo_ros's updateSDFAttributes reads it."""
    models = [root] if root.tag == 'model' else root.findall('model')
    if not models and root.find('world') is not None:
        models = root.find('world').findall('include')[:1]
    return models


class SpawnServices(ServiceGroup):
    """spawn_urdf_model, spawn_sdf_model and delete_model over a Simulator; `ns` is the services' namespace (for
    the messages)."""

    SERVICES = {'spawn_urdf_model': 'SpawnModel', 'spawn_sdf_model': 'SpawnModel', 'delete_model': 'DeleteModel'}

    def __init__(self, rospy, sim, ns):
        super().__init__(rospy, sim)
        self.ns = ns

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
            return srv.SpawnModelResponse(False, self.logged('%s %s' % (SPAWN_INVALID_URDF, spawn_xml.format_problem(
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
        pose = frames.pose_in(req.initial_pose)
        if pose is None:
            return srv.SpawnModelResponse(False, self.logged(
                'SpawnModel: Failure - initial_pose of %s is not finite; give finite numbers' % name))
        with self.sim.lock:
            frame = self.entities.frame_state(req.reference_frame)[0]
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
                return srv.SpawnModelResponse(False, self.logged('%s %s' % (SPAWN_NOT_SDF_OR_URDF, problem)))
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
            return srv.SpawnModelResponse(False, self.logged(str(err)))
        return srv.SpawnModelResponse(True, SPAWN_OK)

    def _not_loaded(self, name, reason):
        """The answer to a spawn whose model did not appear: upstream's status words, then why."""
        return srv.SpawnModelResponse(False, self.logged('%s: %s' % (SPAWN_NOT_LOADED % name, reason)))

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
            self.sim.world.add_sdf_model(model, lambda m: self.rospy.logwarn('spawn_sdf_model: %s' % m))
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

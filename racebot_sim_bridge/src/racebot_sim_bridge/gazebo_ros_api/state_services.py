"""gazebo_ros's state services: get/set_model_state, get/set_link_state, set_model_configuration,
get_world_properties.

As gazebo_ros_api_plugin (noetic) answers them, status messages word for word. Poses are those of each model's
frame in the world (Gazebo's model pose); link names are scoped `model::link`, fixed-joint children merged into
their parent as Gazebo merges them. Names of models, links and reference frames are found as Gazebo's
World::EntityByName finds them (frames.resolve); '', 'world', 'map' and '/map' are the world. Twists in a
reference frame follow upstream's arithmetic per service (frames.py). Where upstream has no check (non-finite
numbers) the answer is ours and says what to change.
"""
from gazebo_msgs import srv
from gazebo_msgs.msg import LinkState
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3

from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup


def pose_msg(pose):
    """geometry_msgs/Pose of a (position, quaternion xyzw) pair."""
    return Pose(position=Point(*pose[0]), orientation=Quaternion(*pose[1]))


def twist_msg(twist):
    """geometry_msgs/Twist of a (linear, angular) pair."""
    return Twist(linear=Vector3(*twist[0]), angular=Vector3(*twist[1]))


class StateServices(ServiceGroup):
    """The state services' handlers over a Simulator."""

    SERVICES = {
        'get_model_state': 'GetModelState', 'set_model_state': 'SetModelState',
        'get_world_properties': 'GetWorldProperties', 'get_link_state': 'GetLinkState',
        'set_link_state': 'SetLinkState', 'set_model_configuration': 'SetModelConfiguration',
    }

    def _seen_from(self, reference, pose, twist):
        """A world pose and twist as seen from the entity `reference` names (get_*_state: relative to it, in its
        axes), as they are for the world's names; None when nothing has that name. Caller holds the lock."""
        frame, frame_twist = self.entities.frame_state(reference)
        if frame is False:
            return None
        if frame is None:
            return pose, twist
        return frames.relative_to(frame, pose), frames.twist_seen_from(frame, frame_twist, twist)

    def get_model_state(self, req):
        res = srv.GetModelStateResponse()
        with self.sim.lock:
            body = self.entities.model_body(req.model_name)
            if body is None:
                return self.fail(res, 'GetModelState: model does not exist',
                                 'GetModelState: model [%s] does not exist' % req.model_name)
            # header.seq: rospy numbers every response itself (upstream counts calls per model)
            res.header.stamp = ros_time(self.rospy.Time, self.sim.time)
            res.header.frame_id = req.relative_entity_name
            seen = self._seen_from(req.relative_entity_name, *self.entities.model_state(body))
            if seen is None:
                res.success = False
                res.status_message = 'GetModelState: reference relative_entity_name not found, did you forget ' \
                                     'to scope the body by model name?'
                return res
        res.pose, res.twist = pose_msg(seen[0]), twist_msg(seen[1])
        res.success, res.status_message = True, 'GetModelState: got properties'
        return res

    def set_model_state(self, req):
        st = req.model_state
        with self.sim.lock:
            body = self.entities.model_body(st.model_name)
            if body is None:
                self.rospy.logerr('Updating ModelState: model [%s] does not exist' % st.model_name)
                return srv.SetModelStateResponse(False, 'SetModelState: model does not exist')
            frame = self.entities.frame_state(st.reference_frame)[0]
            if frame is False:
                self.rospy.logerr('Updating ModelState: for model[%s], specified reference frame entity [%s] does '
                                  'not exist' % (st.model_name, st.reference_frame))
                return srv.SetModelStateResponse(False, 'SetModelState: specified reference frame entity does not '
                                                        'exist')
            pose, twist = frames.pose_in(st.pose), frames.twist_in(st.twist)
            if pose is None or twist is None:
                return srv.SetModelStateResponse(False, self.logged(
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
            seen = self._seen_from(req.reference_frame, *self.entities.state(link))
            if seen is None:
                res.success = False
                res.status_message = 'GetLinkState: reference reference_frame not found, did you forget to scope ' \
                                     'the link by model name?'
                return res
        res.link_state = LinkState(link_name=req.link_name, pose=pose_msg(seen[0]), twist=twist_msg(seen[1]),
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
            pose, twist = frames.pose_in(st.pose), frames.twist_in(st.twist)
            if pose is None or twist is None:
                return srv.SetLinkStateResponse(False, self.logged(
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
            body = self.entities.model_body(req.model_name)
            if body is None:
                self.rospy.logerr('SetModelConfiguration: model [%s] does not exist' % req.model_name)
                return srv.SetModelConfigurationResponse(False, 'SetModelConfiguration: model does not exist')
            if len(req.joint_names) != len(req.joint_positions):
                return srv.SetModelConfigurationResponse(
                    False, 'SetModelConfiguration: joint name and position list have different lengths')
            if not frames.finite(*req.joint_positions):
                return srv.SetModelConfigurationResponse(False, self.logged(
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

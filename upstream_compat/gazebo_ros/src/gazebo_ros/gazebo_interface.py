"""gazebo_ros.gazebo_interface: what scripts import to spawn models, with gazebo_ros's signatures.

Each function waits for its service under `gazebo_namespace` (e.g. '/gazebo'), calls it, logs the
status message and returns the response's success. A failed call is logged and returns False
(gazebo_ros prints it and returns None). Differences: spawn functions take an optional `timeout`
(seconds; None waits for ever, as gazebo_ros does), and set_model_configuration_client does not
sleep 1 s first (gazebo_ros's work-around for a race in Gazebo's spawning that the world server
here does not have: the spawn service returns once the model is in the world).
"""
import rospy
from gazebo_msgs.srv import SetModelConfiguration, SpawnModel

__all__ = ['spawn_sdf_model_client', 'spawn_urdf_model_client', 'set_model_configuration_client']


def _wait(service, timeout):
    rospy.loginfo('Waiting for service %s' % service)
    try:
        rospy.wait_for_service(service, timeout=timeout)
    except rospy.ROSInterruptException:
        raise  # shut down while waiting (a subclass of ROSException): the caller ends
    except rospy.ROSException:
        rospy.logerr('%s did not appear within %g s: is the simulator running (roslaunch gazebo_ros '
                     'empty_world.launch), and is -gazebo_namespace its namespace?' % (service, timeout))
        return False
    return True


def _spawn(kind, model_name, model_xml, robot_namespace, initial_pose, reference_frame, gazebo_namespace,
           timeout):
    service = '%s/spawn_%s_model' % (gazebo_namespace, kind)
    if not _wait(service, timeout):
        return False
    try:
        spawn = rospy.ServiceProxy(service, SpawnModel)
        rospy.loginfo('Calling service %s' % service)
        resp = spawn(model_name, model_xml, robot_namespace, initial_pose, reference_frame)
    except rospy.ServiceException as err:
        rospy.logerr('Service call failed: %s' % err)
        return False
    rospy.loginfo('Spawn status: %s' % resp.status_message)
    return resp.success


def spawn_sdf_model_client(model_name, model_xml, robot_namespace, initial_pose, reference_frame,
                           gazebo_namespace, timeout=None):
    return _spawn('sdf', model_name, model_xml, robot_namespace, initial_pose, reference_frame,
                  gazebo_namespace, timeout)


def spawn_urdf_model_client(model_name, model_xml, robot_namespace, initial_pose, reference_frame,
                            gazebo_namespace, timeout=None):
    return _spawn('urdf', model_name, model_xml, robot_namespace, initial_pose, reference_frame,
                  gazebo_namespace, timeout)


def set_model_configuration_client(model_name, model_param_name, joint_names, joint_positions,
                                   gazebo_namespace):
    service = '%s/set_model_configuration' % gazebo_namespace
    _wait(service, None)
    try:
        configure = rospy.ServiceProxy(service, SetModelConfiguration)
        rospy.loginfo('Calling service %s' % service)
        resp = configure(model_name, model_param_name, joint_names, joint_positions)
    except rospy.ServiceException as err:
        rospy.logerr('Service call failed: %s' % err)
        return False
    rospy.loginfo('Set model configuration status: %s' % resp.status_message)
    return resp.success

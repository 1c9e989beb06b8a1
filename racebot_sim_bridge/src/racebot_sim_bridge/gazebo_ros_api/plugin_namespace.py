"""Where a gazebo_ros plugin puts its topics and services: its robotNamespace, as Gazebo resolves it.

Pure Python. Three rules meet here (gazebo_ros_pkgs noetic-devel):
- spawn: gazebo_ros_api_plugin's spawn_urdf_model / spawn_sdf_model walk the model and give every
  <plugin> WITHOUT a <robotNamespace> element the request's robot_namespace, unless that is empty.
  A plugin's own element wins, even an empty one. spawn_model sends the caller's namespace ('/' at
  the root), so a plugin without the element ends up in '/'.
- each plugin then reads the element with its own default:
  gazebo_ros_control: no element -> the model name; its text otherwise (even '').
  laser, gpu_laser, camera, depth camera (GetRobotNamespace): no element -> ''; an empty element ->
  the model name. The camera family's node handle is robotNamespace + '/' + cameraName.
  imu_sensor: element -> its text + '/'; none -> '/<model name>/'.
  range, bumper: element -> its text + '/' (so an empty one is the root); none -> ''.
- a ros::NodeHandle(ns) resolves a relative ns in the node's namespace (the world server's, '/'
  when it runs at the root); '' is the node's namespace itself.
"""


def after_spawn(own, requested):
    """The plugin's <robotNamespace> text after gazebo_ros's spawn walk, or None when it has none.
    own: the plugin's element text (None when absent); requested: the spawn request's robot_namespace."""
    if own is not None:
        return own
    return requested if requested else None


def resolve(name, node_namespace='/'):
    """The absolute namespace of ros::NodeHandle(name) in a node living in node_namespace: '/' for
    the root, else '/a/b' (no trailing slash, no doubled slashes, as ros::names::clean leaves it)."""
    full = name if name.startswith('/') else '%s/%s' % (node_namespace or '/', name)
    return '/' + '/'.join(p for p in full.split('/') if p)


def control_namespace(own, requested, model_name, node_namespace='/'):
    """gazebo_ros_control's namespace (its controller_manager services and controllers' topics)."""
    text = after_spawn(own, requested)
    return resolve(model_name if text is None else text, node_namespace)


def sensor_namespace(kind, own, requested, model_name, camera_name='', node_namespace='/'):
    """The namespace a sensor plugin of `kind` ('laser', 'camera', 'depth', 'imu') advertises in."""
    text = after_spawn(own, requested)
    if kind == 'imu':
        return resolve('/%s/' % model_name if text is None else text + '/', node_namespace)
    if kind in ('range', 'bumper'):
        return resolve('' if text is None else text + '/', node_namespace)
    if text is None:
        text = ''
    elif text == '':
        text = model_name
    if kind in ('camera', 'depth', 'multicamera'):
        return resolve('%s/%s' % (text, camera_name), node_namespace)
    return resolve(text, node_namespace)


def model_plugin_namespace(kind, own, requested, model_name, node_namespace='/'):
    """The namespace a gazebo_plugins model plugin of `kind` opens its ros::NodeHandle in:
    'drive' (skid_steer_drive, p3d: text + '/', none -> ''), 'planar_move' (text, none -> ''),
    'joint_state_publisher' and 'gazebo_ros' (the GazeboRos helper of gazebo_ros_utils.cpp, which diff_drive
    uses: none or empty -> the model name, then + '/')."""
    text = after_spawn(own, requested)
    if kind in ('joint_state_publisher', 'gazebo_ros'):
        return resolve((text or model_name) + '/', node_namespace)
    if text is None:
        return resolve('', node_namespace)
    return resolve(text + '/' if kind == 'drive' else text, node_namespace)


def name_in(namespace, name):
    """ros::NodeHandle(namespace).advertise(name)'s topic: `name` when absolute, else under `namespace`."""
    return resolve(name if name.startswith('/') else '%s/%s' % (namespace, name))

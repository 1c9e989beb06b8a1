"""spawn_model, with gazebo_ros's command line: puts a URDF or SDF model into the running world.

    spawn_model -urdf|-sdf (-file F | -param P | -stdin | -database NAME) -model NAME
                [-robot_namespace NS] [-reference_frame FRAME] [-gazebo_namespace /gazebo]
                [-x X -y Y -z Z -R R -P P -Y Y] [-J JOINT POSITION]... [-unpause] [-wait MODEL]
                [-timeout SECONDS] [-b] [-package_to_model]

Exits 0 when the model was spawned, 1 (with the reason) otherwise.
"""
import math
import sys

USAGE = __doc__.split('\n\n')[1]


class UsageError(ValueError):
    pass


KINDS = ('-urdf', '-sdf')
SOURCES = ('-file', '-param', '-database', '-stdin')
TEXT_OPTIONS = ('-model', '-robot_namespace', '-reference_frame', '-gazebo_namespace', '-wait')
POSE_OPTIONS = ('-x', '-y', '-z', '-R', '-P', '-Y')


def _number(flag, text):
    try:
        v = float(text)
    except ValueError:
        raise UsageError('%s takes a number, got %r' % (flag, text))
    if not math.isfinite(v):
        raise UsageError('%s must be finite, got %r' % (flag, text))
    return v


def parse_args(argv):
    """gazebo_ros spawn_model's options (single dash) -> dict. Raises UsageError with what to fix."""
    opts = dict(kind=None, source=None, value=None, model=None, robot_namespace='', reference_frame='',
                gazebo_namespace='/gazebo', pose=dict(x=0.0, y=0.0, z=0.0, R=0.0, P=0.0, Y=0.0), joints=[],
                unpause=False, wait=None, timeout=None, bond=False, package_to_model=False)
    i = 0

    def value(flag, count=1):
        if i + count >= len(argv):
            raise UsageError('%s needs %s' % (flag, 'a value' if count == 1 else '%d values' % count))
        return argv[i + 1] if count == 1 else argv[i + 1:i + 1 + count]

    while i < len(argv):
        a = argv[i]
        if a in KINDS:
            if opts['kind'] is not None and opts['kind'] != a[1:]:
                raise UsageError('give one of -urdf or -sdf, not both')
            opts['kind'] = a[1:]
        elif a in ('-gazebo', '-trimesh'):
            raise UsageError('%s models are not supported; use -urdf or -sdf' % a)
        elif a in SOURCES:
            if opts['source'] is not None:
                raise UsageError('give one model source (-file, -param, -database or -stdin), not several')
            opts['source'] = a[1:]
            if a != '-stdin':
                opts['value'] = value(a)
                i += 1
        elif a in TEXT_OPTIONS:
            opts[a[1:]] = value(a)
            i += 1
        elif a in POSE_OPTIONS:
            opts['pose'][a[1:]] = _number(a, value(a))
            i += 1
        elif a == '-J':
            joint, position = value(a, 2)
            opts['joints'].append((joint, _number('-J %s' % joint, position)))
            i += 2
        elif a == '-timeout':
            opts['timeout'] = _number(a, value(a))
            i += 1
        elif a == '-unpause':
            opts['unpause'] = True
        elif a == '-b':
            opts['bond'] = True  # delete the model when this program exits
        elif a == '-package_to_model':
            opts['package_to_model'] = True  # package:// URIs are not resolved by the simulator: no effect
        elif a in ('-h', '--help', '-help'):
            raise UsageError('')
        else:
            raise UsageError('unknown option %r' % a)
        i += 1
    if opts['kind'] is None:
        raise UsageError('say what kind of model: -urdf or -sdf')
    if opts['source'] is None:
        raise UsageError('say where the model comes from: -file FILE, -param PARAM or -stdin')
    if opts['source'] == 'database':
        raise UsageError('-database needs Gazebo\'s model database, which is not available; use -file or -param')
    if not opts['model']:
        raise UsageError('-model NAME is required: the name the model gets in the world')
    return opts


def main(argv=None):
    """Entry point; rospy is imported late so that --help works without ROS."""
    argv = sys.argv if argv is None else argv
    import rospy
    args = rospy.myargv(argv)[1:]
    try:
        opts = parse_args(args)
    except UsageError as err:
        if str(err):
            sys.stderr.write('spawn_model: %s\n' % err)
        sys.stderr.write('usage:\n%s\n' % USAGE)
        sys.exit(2 if str(err) else 0)
    from gazebo_msgs.srv import SetModelConfiguration, SpawnModel
    from geometry_msgs.msg import Pose
    from std_srvs.srv import Empty
    rospy.init_node('spawn_%s' % opts['model'].replace('/', '_').replace('-', '_'), anonymous=True)
    xml = read_model(rospy, opts)
    ns = opts['gazebo_namespace'].rstrip('/')
    if opts['wait']:
        wait_for_model(rospy, ns, opts['wait'])
    service = '%s/spawn_%s_model' % (ns, opts['kind'])
    rospy.loginfo('Waiting for service %s' % service)
    try:
        rospy.wait_for_service(service, timeout=opts['timeout'])
    except rospy.ROSException:
        rospy.logfatal('spawn_model: %s did not appear in %s s; is the simulator running '
                       '(roslaunch racebot_sim_bridge empty_world.launch)?' % (service, opts['timeout']))
        sys.exit(1)
    pose = Pose()
    p = opts['pose']
    pose.position.x, pose.position.y, pose.position.z = p['x'], p['y'], p['z']
    from .sdf_world import rpy_to_quaternion
    q = rpy_to_quaternion(p['R'], p['P'], p['Y'])
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = q
    rospy.loginfo('Calling service %s' % service)
    try:
        res = rospy.ServiceProxy(service, SpawnModel)(opts['model'], xml, opts['robot_namespace'], pose,
                                                      opts['reference_frame'])
    except (rospy.ServiceException, rospy.ROSInterruptException) as err:
        rospy.logfatal('spawn_model: the call to %s failed: %s' % (service, err))
        sys.exit(1)
    rospy.loginfo('Spawn status: %s' % res.status_message)
    if not res.success:
        rospy.logfatal('spawn_model: %s' % res.status_message)
        sys.exit(1)
    if opts['joints']:
        names, positions = zip(*opts['joints'])
        cfg = rospy.ServiceProxy(ns + '/set_model_configuration', SetModelConfiguration)
        r = cfg(opts['model'], opts.get('value') or '', list(names), list(positions))
        if not r.success:
            rospy.logerr('spawn_model: setting the initial joint positions failed: %s' % r.status_message)
            sys.exit(1)
    if opts['unpause']:
        rospy.ServiceProxy(ns + '/unpause_physics', Empty)()
    if opts['bond']:  # -b: the model lives as long as this program
        from gazebo_msgs.srv import DeleteModel
        delete = rospy.ServiceProxy(ns + '/delete_model', DeleteModel)
        rospy.on_shutdown(lambda: delete(opts['model']))
        rospy.spin()
    sys.exit(0)


def read_model(rospy, opts):
    src, value = opts['source'], opts['value']
    if src == 'file':
        try:
            with open(value) as f:
                xml = f.read()
        except OSError as err:
            rospy.logfatal('spawn_model: cannot read model file %s: %s' % (value, err.strerror))
            sys.exit(1)
    elif src == 'param':
        try:
            xml = rospy.get_param(value)
        except KeyError:
            rospy.logfatal("spawn_model: parameter '%s' does not exist; load the model first, e.g. "
                           "<param name=\"%s\" command=\"xacro ...\"/>" % (rospy.resolve_name(value), value))
            sys.exit(1)
    else:
        xml = sys.stdin.read()
    if not isinstance(xml, str) or not xml.strip():
        rospy.logfatal('spawn_model: the model given by -%s %s is empty' % (src, value or ''))
        sys.exit(1)
    return xml


def wait_for_model(rospy, ns, model):
    from gazebo_msgs.srv import GetWorldProperties
    rospy.wait_for_service(ns + '/get_world_properties')
    props = rospy.ServiceProxy(ns + '/get_world_properties', GetWorldProperties)
    rospy.loginfo('Waiting for model %s to appear' % model)
    while not rospy.is_shutdown() and model not in props().model_names:
        time_sleep(0.5)


def time_sleep(s):
    import time
    time.sleep(s)  # wall time: this runs before sim time moves


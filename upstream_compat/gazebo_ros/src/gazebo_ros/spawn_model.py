"""spawn_model: gazebo_ros's command line for putting a URDF or SDF model into the running world.

    spawn_model (-urdf | -sdf) (-file FILE | -param PARAM | -database MODEL | -stdin) -model NAME
                [-reference_frame FRAME] [-gazebo_namespace /gazebo] [-robot_namespace NS]
                [-unpause] [-wait MODEL] [-x X] [-y Y] [-z Z] [-R R] [-P P] [-Y Y]
                [-J JOINT POSITION]... [-package_to_model] [-b] [-timeout SECONDS]

As gazebo_ros's scripts/spawn_model (noetic-devel) does it, in its order and with its log lines:
-wait waits for a model in <gazebo_namespace>/model_states; the XML is read, checked and written
back (-package_to_model turns every <mesh filename="package://..."> into model://...); -database NAME
sends Gazebo's <include><uri>model://NAME</uri></include> world snippet, which the world server
looks up in the Gazebo model path; the spawn service gets the caller's namespace (`/` at the root)
as robot_namespace unless -robot_namespace says otherwise; -J sets joints once spawned; -unpause
unpauses; -b keeps the program running and deletes the model when it is shut down.

Exit codes as upstream's: 0 spawned, 1 the model could not be read or spawned, 2 a bad command
line (argparse's message and usage). racebot's additions: numbers must be finite (exit 2 instead of a
spawn that fails later), a missing -param says what to do instead of a traceback, and -timeout
bounds the wait for the spawn service (upstream waits forever, which stays the default).
"""
import argparse
import math
import os
import sys
import time
import xml.etree.ElementTree as ET
from urllib.parse import SplitResult, urlsplit

# What gazebo_ros sends for -database NAME: a world holding one include of the named model.
MODEL_DATABASE_TEMPLATE = """\
<sdf version="1.4">
    <world name="default">
        <include>
            <uri>model://{}</uri>
        </include>
    </world>
</sdf>"""

WAIT_POLL_PERIOD = 0.1  # wall seconds between looks at model_states for -wait (upstream: 10 Hz)


def _finite_number(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError('expected a number, got %r' % text)
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError('must be a finite number, got %r' % text)
    return value


def _seconds(text):
    value = _finite_number(text)
    if value <= 0:
        raise argparse.ArgumentTypeError('must be more than 0 seconds, got %r' % text)
    return value


def build_parser(namespace='/'):
    """gazebo_ros spawn_model's argparse parser; `namespace` is the -robot_namespace default (the
    caller's ROS namespace, as upstream takes it from rospy.get_namespace())."""
    p = argparse.ArgumentParser(prog='spawn_model', description='Spawn a model in gazebo using the ROS API')
    kind = p.add_mutually_exclusive_group(required=True)
    kind.add_argument('-urdf', action='store_true', help='Incoming xml is in urdf format')
    kind.add_argument('-sdf', action='store_true', help='Incoming xml is in sdf format')
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument('-file', metavar='FILE_NAME', help='Load model xml from file')
    source.add_argument('-param', metavar='PARAM_NAME', help='Load model xml from ROS parameter')
    source.add_argument('-database', metavar='MODEL_NAME',
                        help='Load model XML from specified model in Gazebo Model Database '
                             '(here: the Gazebo model path, GAZEBO_MODEL_PATH and gazebo_model_path exports)')
    source.add_argument('-stdin', action='store_true', help='Load model from stdin')
    p.add_argument('-model', required=True, metavar='MODEL_NAME', help='Name of model to spawn')
    p.add_argument('-reference_frame', default='',
                   help='Name of the model/body where initial pose is defined. '
                        'If left empty or specified as "world", gazebo world frame is used')
    p.add_argument('-gazebo_namespace', default='/gazebo',
                   help='ROS namespace of gazebo offered ROS interfaces.  Defaults to /gazebo/')
    p.add_argument('-robot_namespace', default=namespace, help='change ROS namespace of gazebo-plugins')
    p.add_argument('-unpause', action='store_true', help='unpause physics after spawning model')
    p.add_argument('-wait', metavar='MODEL_NAME', help='wait for model to exist')
    for axis, what in (('x', 'x component of initial position, meters'),
                       ('y', 'y component of initial position, meters'),
                       ('z', 'z component of initial position, meters'),
                       ('R', 'roll angle of initial orientation, radians'),
                       ('P', 'pitch angle of initial orientation, radians'),
                       ('Y', 'yaw angle of initial orientation, radians')):
        p.add_argument('-' + axis, type=_finite_number, default=0.0, help=what)
    p.add_argument('-J', dest='joints', default=[], action='append', nargs=2,
                   metavar=('JOINT_NAME', 'JOINT_POSITION'),
                   help='initialize the specified joint at the specified position')
    p.add_argument('-package_to_model', action='store_true',
                   help='convert urdf <mesh filename="package://..." to <mesh filename="model://..."')
    p.add_argument('-b', dest='bond', action='store_true',
                   help='bond to gazebo and delete the model when this program is interrupted')
    p.add_argument('-timeout', type=_seconds, default=None,
                   help='racebot: give up when the spawn service has not appeared after this many '
                        'seconds (default: wait for ever, as gazebo_ros does)')
    return p


def parse_args(argv, namespace='/'):
    """The options (argparse.Namespace); -J positions become floats. A bad command line exits 2
    with argparse's message, as upstream's."""
    parser = build_parser(namespace)
    args = parser.parse_args(argv)
    joints = []
    for name, position in args.joints:
        try:
            joints.append((name, _finite_number(position)))
        except argparse.ArgumentTypeError as err:
            parser.error('argument -J: joint %s: %s' % (name, err))
    args.joints = joints
    return args


def package_to_model(root):
    """Every <mesh filename="package://PKG/..."> below `root` becomes model://PKG/... (in place)."""
    for mesh in root.iter('mesh'):
        filename = mesh.get('filename')
        if filename is None:
            continue
        url = urlsplit(filename)
        if url.scheme == 'package':
            mesh.set('filename', SplitResult('model', *url[1:]).geturl())
    return root


def prepare_xml(text, to_model=False):
    """The model XML as the spawn service gets it: parsed (ET.ParseError when it is not XML),
    meshes rewritten if asked, written back."""
    root = ET.fromstring(text)
    if to_model:
        package_to_model(root)
    return ET.tostring(root, encoding='unicode')


def quaternion_from_euler(roll, pitch, yaw):
    """(x, y, z, w) of fixed-axis roll, then pitch, then yaw (tf.transformations' default 'sxyz'):
    the simulator's own rotation maths (racebot_sim_bridge runs behind this gazebo_ros anyway)."""
    from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion
    return rpy_to_quaternion(roll, pitch, yaw)


class SpawnModelNode:
    """One run of spawn_model: `run()` returns the exit code."""

    def __init__(self, args, rospy):
        self.args = args
        self.rospy = rospy
        self.model_exists = False

    def run(self):
        rospy, args = self.rospy, self.args
        if args.wait and not self.wait_for_model():
            return 0  # shut down while waiting: upstream ends quietly too
        model_xml = self.load_xml()
        if model_xml is None:
            return 1
        try:
            model_xml = prepare_xml(model_xml, args.package_to_model)
        except ET.ParseError as err:
            rospy.logerr('Invalid XML: {}'.format(err))
            return 1
        from geometry_msgs.msg import Pose, Quaternion
        from gazebo_ros import gazebo_interface
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = args.x, args.y, args.z
        pose.orientation = Quaternion(*quaternion_from_euler(args.R, args.P, args.Y))
        spawn = gazebo_interface.spawn_urdf_model_client if args.urdf else gazebo_interface.spawn_sdf_model_client
        if not spawn(args.model, model_xml, args.robot_namespace, pose, args.reference_frame,
                     args.gazebo_namespace, timeout=args.timeout):
            rospy.logerr('Spawn service failed. Exiting.')
            return 1
        if args.joints:
            names, positions = zip(*args.joints)
            if not gazebo_interface.set_model_configuration_client(args.model, '', list(names), list(positions),
                                                                   args.gazebo_namespace):
                rospy.logerr('SetModelConfiguration service failed. Exiting.')
                return 1
        if args.unpause and not self.unpause():
            return 1
        if args.bond:
            rospy.on_shutdown(self.delete_model)
            rospy.loginfo('Waiting for shutdown to delete model {}'.format(args.model))
            rospy.spin()
        return 0

    def wait_for_model(self):
        """Until -wait's model is in model_states (True), or shutdown (False). Polled in wall time:
        ROS time stands still while the world is paused."""
        from gazebo_msgs.msg import ModelStates
        rospy, name = self.rospy, self.args.wait

        def on_states(msg):
            self.model_exists = name in msg.name
        sub = rospy.Subscriber('%s/model_states' % self.args.gazebo_namespace, ModelStates, on_states, queue_size=1)
        rospy.loginfo('Waiting for model {} before proceeding.'.format(name))
        while not rospy.is_shutdown() and not self.model_exists:
            time.sleep(WAIT_POLL_PERIOD)
        sub.unregister()
        return self.model_exists

    def load_xml(self):
        """The model's XML text, or None after logging why not."""
        rospy, args = self.rospy, self.args
        if args.file:
            rospy.loginfo('Loading model XML from file %s' % args.file)
            if not os.path.exists(args.file):
                rospy.logfatal('Error: specified file %s does not exist', args.file)
                return None
            if not os.path.isfile(args.file):
                rospy.logfatal('Error: specified file %s is not a file', args.file)
                return None
            try:
                with open(args.file) as f:
                    text = f.read()
            except (OSError, UnicodeDecodeError) as err:
                rospy.logerr('Error reading file {}: {}'.format(args.file, err))
                return None
            if text == '':
                rospy.logerr('Error: file %s is empty', args.file)
                return None
            return text
        if args.param:
            rospy.loginfo('Loading model XML from ros parameter %s' % args.param)
            try:
                text = rospy.get_param(args.param)
            except KeyError:
                rospy.logfatal("Error: parameter '%s' does not exist; load the model first, e.g. "
                               "<param name=\"%s\" command=\"xacro ...\"/>"
                               % (rospy.resolve_name(args.param), args.param))
                return None
            if not isinstance(text, str) or text.strip() == '':
                rospy.logerr('Error: param does not exist or is empty (-param %s)' % rospy.resolve_name(args.param))
                return None
            return text
        if args.database:
            rospy.loginfo('Loading model XML from Gazebo Model Database')
            return MODEL_DATABASE_TEMPLATE.format(args.database)
        rospy.loginfo('Loading model XML from stdin')
        text = sys.stdin.read()
        if text == '':
            rospy.logerr('Error: stdin buffer was empty')
            return None
        return text

    def unpause(self):
        from std_srvs.srv import Empty
        rospy, name = self.rospy, '%s/unpause_physics' % self.args.gazebo_namespace
        rospy.loginfo('Unpausing physics')
        try:
            rospy.wait_for_service(name)
            rospy.ServiceProxy(name, Empty)()
        except (rospy.ServiceException, rospy.ROSException) as err:
            rospy.logerr('Unpause physics service call failed: {}'.format(err))
            return False
        return True

    def delete_model(self):
        """-b: on shutdown, the model goes with us."""
        from gazebo_msgs.srv import DeleteModel
        rospy = self.rospy
        rospy.loginfo('Deleting model {}'.format(self.args.model))
        try:
            rospy.ServiceProxy('%s/delete_model' % self.args.gazebo_namespace, DeleteModel)(model_name=self.args.model)
        except (rospy.ServiceException, rospy.ROSException) as err:
            rospy.logerr('Delete model service call failed: %s', err)


def main(argv=None):
    import rospy
    argv = rospy.myargv(sys.argv if argv is None else argv)
    args = parse_args(argv[1:], rospy.get_namespace())
    rospy.init_node('spawn_model', anonymous=True)
    try:
        code = SpawnModelNode(args, rospy).run()
    except rospy.ROSInterruptException:
        code = 1  # shut down while waiting for a service
    sys.exit(code)

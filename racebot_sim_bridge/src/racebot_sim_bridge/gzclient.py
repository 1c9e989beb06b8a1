"""gzclient: the window alone, attaching to a running world server. `rosrun gazebo_ros gzclient`.

A node (default name gazebo_gui, as empty_world.launch names it) that finds the world server
`gazebo` of its own namespace (the private parameter ~gazebo_namespace names another), waits until
that server is up, attaches to it (viewer.AttachedWindows: the socket named by the server's
parameter `gzclient_address`) and shows PyBullet's window of the world (viewer_process.Window),
niced (NICENESS) so that physics and cameras come first. It only watches: closing it never stops
the server, and any number of windows may be attached at once.

Command line: gzclient's own options are accepted: --verbose (debug logging), -g/--gui-plugin
PLUGIN (Gazebo GUI plugins: none can load here, each named once in the log), -h/--help, -v/--version.

It ends:
  exit 0  the window was closed (or killed), Ctrl-C, the world server shut down, or there is no
          display (DISPLAY unset: said once; the world server runs on without a window);
  exit 1  the X display cannot be opened, the window cannot open, or the world server was lost
          (its connection broke without a word: crashed or killed); each said in the log.
"""
import os
import signal
import socket
import sys
import time
from multiprocessing.connection import Connection

NODE_NAME = 'gazebo_gui'
ADDRESS_PARAM = 'gzclient_address'  # the world server's private parameter naming its window socket
NICENESS = 10
WAIT_PERIOD = 0.5                   # s between looks for the world server
VERSION = 'racebot gzclient (a window onto racebot_sim_bridge\'s PyBullet world server, for Gazebo 11 users)'
USAGE = """usage: gzclient [--verbose] [-g PLUGIN]... [-h] [-v]   (ROS remaps as for any node)
  Shows the world of the running world server <namespace>/gazebo (~gazebo_namespace: another).
  --verbose            debug messages
  -g, --gui-plugin P   a Gazebo GUI plugin: none can load here; named once in the log
  -h, --help           this text
  -v, --version        the version"""


class UsageError(ValueError):
    pass


def parse_args(argv):
    """gzclient's options (argv without the program name and ROS remaps) -> dict(verbose, plugins,
    help, version, ignored). Unknown options are kept in `ignored` (gzclient has many that mean
    nothing here); a -g without its plugin is a UsageError."""
    opts = dict(verbose=False, plugins=[], help=False, version=False, ignored=[])
    it = iter(argv)
    for arg in it:
        if arg == '--verbose':
            opts['verbose'] = True
        elif arg in ('-g', '--gui-plugin'):
            plugin = next(it, None)
            if plugin is None or plugin.startswith('-'):
                raise UsageError('%s needs a plugin file name' % arg)
            opts['plugins'].append(plugin)
        elif arg.startswith('--gui-plugin='):
            opts['plugins'].append(arg.split('=', 1)[1])
        elif arg in ('-h', '--help'):
            opts['help'] = True
        elif arg in ('-v', '--version'):
            opts['version'] = True
        elif arg.strip():
            opts['ignored'].append(arg)
    return opts


def address_param(namespace):
    """The parameter holding the window socket of the world server in `namespace` (resolved)."""
    return namespace.rstrip('/') + '/' + ADDRESS_PARAM


def connect(address):
    """A Connection to the world server's window socket, or None if nobody answers there."""
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        sock.setblocking(True)  # whatever socket.setdefaulttimeout says (rospy sets one)
        sock.connect(address)
    except OSError:
        sock.close()
        return None
    return Connection(sock.detach())


def quiet_c_stdout():
    """PyBullet's C code chatters on stdout (GL details, thread starts): file descriptor 1 goes to
    /dev/null, and Python's sys.stdout (our log lines) keeps what it was."""
    sys.stdout.flush()
    kept = os.dup(1)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.close(null)
    sys.stdout = os.fdopen(kept, 'w', buffering=1)


def _interrupt(*_):
    raise KeyboardInterrupt


class Gzclient(object):
    def __init__(self, rospy):
        self.rospy = rospy
        namespace = rospy.get_param('~gazebo_namespace', 'gazebo')
        self.namespace = rospy.resolve_name(str(namespace))
        self.param = address_param(self.namespace)

    def wait_for_server(self):
        """Waits (as long as it takes: a launch starts us with the server, which loads its world
        first) until the world server answers -> Connection, or None on shutdown."""
        rospy = self.rospy
        said = None
        while not rospy.is_shutdown():
            try:
                address = rospy.get_param(self.param)
            except KeyError:
                address, why = None, 'it has not set %s yet' % self.param
            conn = connect(str(address)) if address else None
            if conn is not None:
                return conn
            if address:
                why = 'nobody answers at %s (%s): it has not started yet, or it was stopped' % (address, self.param)
            if why != said:
                rospy.loginfo('waiting for the world server %s: %s' % (self.namespace, why))
                said = why
            time.sleep(WAIT_PERIOD)
        return None

    def run(self):
        """-> exit code."""
        from . import viewer_process
        from .physics import PhysicsError
        rospy = self.rospy
        conn = self.wait_for_server()
        if conn is None:
            return 0
        watch = viewer_process.XConnectionWatch()
        try:
            window = viewer_process.Window()
        except PhysicsError as err:
            rospy.logerr('the window could not open (%s); the world server runs on without it' % err)
            conn.close()
            return 1
        try:
            conn.send(('hello', os.getpid(), rospy.get_name()))
            rospy.loginfo('attached to the world server %s: showing its world (process %d, niced %+d)' % (
                self.namespace, os.getpid(), NICENESS))
            how, why = viewer_process.serve(conn, window, watch.fd)
        except (EOFError, OSError) as err:
            how, why = viewer_process.LOST, 'its connection closed (%s)' % type(err).__name__
        except KeyboardInterrupt:
            rospy.loginfo('interrupted: closing the window; the world server %s runs on' % self.namespace)
            conn.close()
            window.close()
            return 0
        conn.close()
        if how == viewer_process.CLOSED:
            rospy.loginfo('the window was closed (%s); the world server %s runs on' % (why, self.namespace))
            # PyBullet's drawing thread is parked in the X error handler: disconnecting would wait for it
            rospy.signal_shutdown('window closed')
            sys.stdout.flush()
            os._exit(0)
        window.close()
        if how == viewer_process.STOPPED:
            rospy.loginfo('the world server %s said: %s. Closing the window' % (self.namespace, why))
            return 0
        rospy.logerr('lost the world server %s: %s. Closing the window' % (self.namespace, why))
        return 1


def main(argv=None):
    import rospy
    argv = rospy.myargv(list(sys.argv if argv is None else argv))
    try:
        opts = parse_args(argv[1:])
    except UsageError as err:
        sys.stderr.write('gzclient: %s\n%s\n' % (err, USAGE))
        sys.exit(2)
    if opts['help'] or opts['version']:
        print(USAGE if opts['help'] else VERSION)
        sys.exit(0)
    signal.signal(signal.SIGTERM, _interrupt)  # roslaunch's escalation: end as on Ctrl-C
    quiet_c_stdout()  # before rospy's log handler takes sys.stdout
    try:
        rospy.init_node(NODE_NAME, disable_rostime=True, disable_signals=True,
                        log_level=rospy.DEBUG if opts['verbose'] else rospy.INFO)
        for plugin in opts['plugins']:
            rospy.loginfo('gzclient -g %s: Gazebo GUI plugins cannot load here; ignored' % plugin)
        for arg in opts['ignored']:
            rospy.loginfo('gzclient option %s has no meaning here; ignored' % arg)
        from .viewer_process import display_problem
        problem = display_problem()
        if problem is not None:
            unset = not os.environ.get('DISPLAY')
            (rospy.loginfo if unset else rospy.logerr)(
                'no window: %s. The world server runs on without one%s' % (
                    problem, '' if unset else '; set DISPLAY to a display you can open'))
            code = 0 if unset else 1
        else:
            try:
                os.nice(NICENESS)
            except OSError:
                pass
            code = Gzclient(rospy).run()
    except KeyboardInterrupt:
        code = 0
    rospy.signal_shutdown('gzclient done')
    sys.exit(code)

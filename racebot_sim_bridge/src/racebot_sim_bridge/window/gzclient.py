"""gzclient: the window alone, attaching to a running world server. `rosrun gazebo_ros gzclient`.

A node (default name gazebo_gui, as empty_world.launch names it) that finds the world server
`gazebo` of its own namespace (the private parameter ~gazebo_namespace names another), waits until
that server is up, connects to it (viewer.AttachedWindows: the socket named by the server's
parameter `gzclient_address`) and hands that connection to the window, PyBullet's GUI client in a
process of its own (viewer_process, a fresh interpreter without rospy's threads), niced (NICENESS)
with this node so that physics and cameras come first. The window's exit code says how it ended.
It only watches: closing it never stops the server, and any number of windows may be attached.

Command line: gzclient's own options are accepted: --verbose (debug logging), -g/--gui-plugin
PLUGIN (Gazebo GUI plugins: none can load here, each named once in the log), -h/--help, -v/--version.

It ends:
  exit 0  the window was closed (or killed), Ctrl-C, the world server shut down, or there is no
          display (DISPLAY unset: said once; the world server runs on without a window);
  exit 1  the X display cannot be opened, the window cannot open or crashed, or the world server was lost
          (its connection broke without a word: crashed or killed); each said in the log.
"""
import ctypes
import ctypes.util
import os
import signal
import socket
import sys
import time
from multiprocessing.connection import Connection

from racebot_sim_bridge.engine import child_process

NODE_NAME = 'gazebo_gui'
ADDRESS_PARAM = 'gzclient_address'  # the world server's private parameter naming its window socket
NICENESS = 10
WAIT_PERIOD = 0.5                   # s between looks for the world server
WINDOW_MODULE = 'racebot_sim_bridge.window.viewer_process'
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


def connect_socket(address):
    """A socket connected to the world server's window socket, or None if nobody answers there."""
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        sock.setblocking(True)  # whatever socket.setdefaulttimeout says (rospy sets one)
        sock.connect(address)
    except OSError:
        sock.close()
        return None
    return sock


def connect(address):
    """connect_socket as a multiprocessing Connection (what the window speaks), or None."""
    sock = connect_socket(address)
    return Connection(sock.detach()) if sock is not None else None


def say_hello(conn, pid, node_name):
    """Says who the window is, for the window process `pid`, on `conn` (this process's copy of the window's
    connection), and closes that copy."""
    try:
        conn.send(('hello', pid, node_name))
    except OSError:
        pass  # the server went: the window finds out and says so
    finally:
        conn.close()


def _libx11():
    try:
        return ctypes.CDLL(ctypes.util.find_library('X11') or 'libX11.so.6')
    except OSError:
        return None


def display_problem(display=None):
    """None if an X display can be opened (DISPLAY, or `display`), else why not, in words."""
    name = display if display is not None else os.environ.get('DISPLAY', '')
    if not name:
        return 'there is no display (DISPLAY is unset)'
    x11 = _libx11()
    if x11 is None:
        return None  # no libX11 to ask: PyBullet will say
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    handle = x11.XOpenDisplay(name.encode())
    if not handle:
        return 'the X display %r cannot be opened (no X server there, or no permission: see xhost/XAUTHORITY)' % name
    x11.XCloseDisplay(handle)
    return None



def _interrupt(*_):
    raise KeyboardInterrupt


class Gzclient:
    def __init__(self, rospy):
        self.rospy = rospy
        namespace = rospy.get_param('~gazebo_namespace', 'gazebo')
        self.namespace = rospy.resolve_name(str(namespace))
        self.param = address_param(self.namespace)

    def wait_for_server(self):
        """Waits (as long as it takes: a launch starts us with the server, which loads its world
        first) until the world server answers -> a connected socket, or None on shutdown."""
        rospy = self.rospy
        said = None
        while not rospy.is_shutdown():
            try:
                address = rospy.get_param(self.param)
            except KeyError:
                address, why = None, 'it has not set %s yet' % self.param
            sock = connect_socket(str(address)) if address else None
            if sock is not None:
                return sock
            if address:
                why = 'nobody answers at %s (%s): it has not started yet, or it was stopped' % (address, self.param)
            if why != said:
                rospy.loginfo('waiting for the world server %s: %s' % (self.namespace, why))
                said = why
            time.sleep(WAIT_PERIOD)
        return None

    def run(self):
        """-> exit code."""
        from racebot_sim_bridge.window.viewer_process import (EXIT_CLOSED, EXIT_CRASHED, EXIT_LOST, EXIT_NO_WINDOW,
                                                              EXIT_STOPPED)
        rospy = self.rospy
        sock = self.wait_for_server()
        if sock is None:
            return 0
        # The hello goes from here, for the window, as soon as its process exists: the window opens PyBullet's GUI
        # (seconds of software OpenGL on a busy machine) before it reads anything, and the world server drops a
        # connection that has not said who it is within viewer.HELLO_TIMEOUT. Nothing else is written on this
        # side: the window's first message, 'shown', answers the server's first update, which follows the hello.
        ours = Connection(os.dup(sock.fileno()))
        window, _ = child_process.start(WINDOW_MODULE, args=[rospy.get_name()], connection=sock)
        say_hello(ours, window.pid, rospy.get_name())
        rospy.loginfo('attached to the world server %s: its window is process %d (niced %+d)' % (
            self.namespace, window.pid, NICENESS))
        try:
            code = window.wait()
        except KeyboardInterrupt:
            rospy.loginfo('interrupted: closing the window; the world server %s runs on' % self.namespace)
            child_process.stop(window, None)
            return 0
        if code == EXIT_CLOSED or code < 0:
            rospy.loginfo('the window was closed (%s); the world server %s runs on' % (
                'its X connection closed' if code == EXIT_CLOSED else 'its process was killed, signal %d' % -code,
                self.namespace))
            return 0
        if code == EXIT_STOPPED:
            rospy.loginfo('the world server %s shut down: the window closes with it' % self.namespace)
            return 0
        if code == EXIT_LOST:
            rospy.logerr('lost the world server %s: its connection closed without a word (it crashed or was '
                         'killed). The window closed' % self.namespace)
        elif code == EXIT_NO_WINDOW:
            rospy.logerr('the window could not open (see the line above); the world server runs on without it')
        else:
            rospy.logerr('the window process ended with exit code %d%s; the world server runs on' % (
                code, ' (it crashed: see the traceback above)' if code == EXIT_CRASHED else ''))
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
    try:
        rospy.init_node(NODE_NAME, disable_rostime=True, disable_signals=True,
                        log_level=rospy.DEBUG if opts['verbose'] else rospy.INFO)
        for plugin in opts['plugins']:
            rospy.loginfo('gzclient -g %s: Gazebo GUI plugins cannot load here; ignored' % plugin)
        for arg in opts['ignored']:
            rospy.loginfo('gzclient option %s has no meaning here; ignored' % arg)
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

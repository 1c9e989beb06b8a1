"""gazebo: the world server and its window together. `rosrun gazebo_ros gazebo [gzserver options] [WORLD]`.

As gazebo_ros's `gazebo` script does with gzserver and gzclient: the world server (world_server.py,
gzserver's command line and every ROS remap given; node name gazebo unless remapped) starts in
the background, then the window (gzclient.py: node gazebo_gui in the same namespace, attached to
that server; --verbose and -g go to it too) in the foreground. Closing the window stops the world
server (SIGINT), as closing Gazebo's window ends `gazebo`. Without a display, or if the window
cannot open, the world server runs on alone (said once). Ctrl-C or SIGTERM stop both; either dies
with this process (PR_SET_PDEATHSIG). Exits with the world server's exit code.
"""
import signal
import subprocess
import sys
import time

from racebot_sim_bridge.engine.child_process import die_with_parent

SERVER_MAIN = 'import sys; from %s import main; sys.exit(main())'  # % the world server's module
CLIENT_MAIN = 'from racebot_sim_bridge.window.gzclient import main; main()'
SERVER_NAME = 'gazebo'              # the world server's node name unless remapped
CLIENT_NAME = 'gazebo_gui'
CLIENT_REMAPS = ('__ns', '__master', '__ip', '__hostname')  # where the window's node lives, as the server
STOP_TIMEOUT = 20.0                 # s for a child to end after SIGINT, then SIGTERM
POLL = 0.1


def split_args(argv):
    """The command line (without the program name) -> (server's arguments, window's arguments)."""
    server, client = [], ['__name:=%s' % CLIENT_NAME]
    server_name = SERVER_NAME
    it = iter(argv)
    for arg in it:
        if arg in ('-g', '--gui-plugin'):
            client += [arg, next(it, '')]
            continue
        if arg.startswith('--gui-plugin='):
            client.append(arg)
            continue
        server.append(arg)
        if arg == '--verbose':
            client.append(arg)
        elif ':=' in arg:
            key, value = arg.split(':=', 1)
            if key in CLIENT_REMAPS:
                client.append(arg)
            elif key == '__name':
                server_name = value
    if server_name != SERVER_NAME:
        client.append('_gazebo_namespace:=%s' % server_name)
    return server, client


def _start(code, args):
    return subprocess.Popen([sys.executable, '-c', code] + list(args), preexec_fn=die_with_parent)


def _say(text):
    sys.stderr.write('gazebo: %s\n' % text)
    sys.stderr.flush()


def _stop(process, sig=signal.SIGINT):
    """Asks a child to end (sig), then SIGTERM, then SIGKILL; -> its exit code."""
    for step in (sig, signal.SIGTERM, signal.SIGKILL):
        if process.poll() is not None:
            break
        process.send_signal(step)
        try:
            process.wait(STOP_TIMEOUT if step != signal.SIGKILL else None)
        except subprocess.TimeoutExpired:
            continue
    return process.returncode


def _stop_when_done(server):
    """Waits for the world server to end by itself (Ctrl-C, rosnode kill); -> its exit code."""
    while server.poll() is None:
        time.sleep(POLL)
    return server.returncode


def main(argv=None, server_module='racebot_sim_bridge.world_server'):
    """server_module: whose main() is the world server (gazebo_ros's gzserver: gazebo_ros.server)."""
    from racebot_sim_bridge.window.gzclient import display_problem
    server_args, client_args = split_args(list(sys.argv if argv is None else argv)[1:])
    children = []

    def forward(signum, _frame):  # Ctrl-C, roslaunch's SIGINT/SIGTERM: the children end as they would alone
        for child in children:
            if child.poll() is None:
                child.send_signal(signum)
    signal.signal(signal.SIGINT, forward)
    signal.signal(signal.SIGTERM, forward)

    server = _start(SERVER_MAIN % server_module, server_args)
    children.append(server)
    problem = display_problem()
    if problem is not None:
        _say('no window: %s; the world server runs without one' % problem)
        sys.exit(_stop_when_done(server))
    client = _start(CLIENT_MAIN, client_args)
    children.append(client)
    while server.poll() is None and client.poll() is None:
        time.sleep(POLL)
    if server.poll() is None:  # the window ended first
        if client.returncode == 0:
            _say('the window closed: stopping the world server')
            sys.exit(_stop(server))
        _say('the window ended with exit code %d: the world server runs on without it' % client.returncode)
        sys.exit(_stop_when_done(server))
    try:
        client.wait(5.0)  # the server told it it stops: it ends by itself
    except subprocess.TimeoutExpired:
        _stop(client)
    sys.exit(server.returncode)

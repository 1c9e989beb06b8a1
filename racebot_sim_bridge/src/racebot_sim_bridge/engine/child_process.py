"""Helper processes (the render worker, gzclient's window): how they start and die; `die_with_parent`
for the processes the `gazebo` command starts (gazebo_command.py).

No rospy here. A helper is `python -m racebot_sim_bridge.<module> FD`, a fresh interpreter (not a
multiprocessing fork of a process with rospy's threads, nor a spawn that would re-run the node's
script), talking over one end of a socket pair. It dies with the simulator however the simulator
dies (PR_SET_PDEATHSIG), and leaves Ctrl-C to the simulator, which stops it.
"""
from __future__ import annotations

import ctypes
import os
import signal
import socket
import subprocess
import sys
import threading
from collections.abc import Mapping, Sequence
from multiprocessing.connection import Connection

PACKAGE_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def start(module: str, env: Mapping[str, str] | None = None, args: Sequence[str] = (),
          connection: socket.socket | None = None) -> tuple[subprocess.Popen, Connection | None]:
    """Starts `python -m <module> FD [args]` -> (subprocess.Popen, Connection to it). `env`: variables
    to add to this process's environment. Its stdout is discarded (PyBullet's plugins chatter there);
    stderr is ours. `connection`: a connected socket (gzclient's to the world server) to hand over as
    FD instead of a new pair; this process's copy is closed and no Connection returned."""
    if connection is None:
        parent, child = socket.socketpair()
        # Blocking, whatever socket.setdefaulttimeout says (rospy sets one): Connection reads raw fds.
        parent.setblocking(True)
    else:
        parent, child = None, connection
    child.setblocking(True)
    full_env = dict(os.environ)
    full_env.update(env or {})
    # The helper imports this very package, wherever it was imported from here (tests, devel).
    full_env['PYTHONPATH'] = os.pathsep.join(
        [PACKAGE_ROOT] + [p for p in full_env.get('PYTHONPATH', '').split(os.pathsep) if p])
    try:
        process = subprocess.Popen([sys.executable, '-m', module, str(child.fileno())] + list(args),
                                   pass_fds=[child.fileno()], env=full_env, stdin=subprocess.DEVNULL,
                                   stdout=subprocess.DEVNULL, close_fds=True)
    except BaseException:
        if parent is not None:
            parent.close()
        raise
    finally:
        child.close()
    return process, (Connection(parent.detach()) if parent is not None else None)


def ask_to_stop(process: subprocess.Popen | None, conn: Connection | None, wait: float = 2.0,
                lock: threading.Lock | None = None) -> None:
    """Sends the helper ('stop',) (under `lock` when other threads send too) and gives it `wait` s
    to exit; a helper already gone is no error. Follow with stop()."""
    if conn is None or process is None:
        return
    try:
        if lock is not None:
            with lock:
                conn.send(('stop',))
        else:
            conn.send(('stop',))
        process.wait(wait)
    except (OSError, EOFError, subprocess.TimeoutExpired):
        pass


def stop(process: subprocess.Popen | None, conn: Connection | None, wait: float = 5.0) -> None:
    """Closes the connection and ends the process: SIGTERM, then SIGKILL after `wait` s."""
    if conn is not None:
        try:
            conn.close()
        except OSError:
            pass
    if process is not None and process.poll() is None:
        process.terminate()
        try:
            process.wait(wait)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


def die_with_parent() -> None:
    """SIGTERM to this process when the thread that started it ends (PR_SET_PDEATHSIG). Also usable
    as subprocess's preexec_fn (in a parent without threads)."""
    try:
        libc = ctypes.CDLL('libc.so.6', use_errno=True)
        libc.prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def helper_main(fd: int) -> Connection:
    """In the helper, first thing: the Connection to the simulator from its FD; dies with the
    simulator (SIGTERM when the thread that started it ends), ignores Ctrl-C, exits on SIGTERM."""
    die_with_parent()
    if os.getppid() == 1:  # the simulator died before prctl: nobody would signal us
        os._exit(0)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, lambda *_: os._exit(0))
    return Connection(fd)

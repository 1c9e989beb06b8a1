"""The window of gzclient (gzclient.py): PyBullet's GUI client showing what a world server sends it.

No rospy here. The window holds a world_copy.WorldCopy of the simulated world. For each update the
world server sends (viewer.AttachedWindows), it brings the copy's bodies and poses up to date (only
what moved: every call into the GUI client waits for its next frame), keeps the camera on the car,
and answers, which tells the server it may send the next.

Closing the window: PyBullet's window sets no WM_PROTOCOLS, so a window manager's close button kills
its X connection (XKillClient), and Xlib's default answer is exit(1) from PyBullet's drawing thread.
`XConnectionWatch` replaces that answer: the main thread hears of it and gzclient ends as a window
closed by its user should, exit code 0.
"""
import ctypes
import ctypes.util
import os
import time
from multiprocessing.connection import wait

import pybullet as pb

from .physics import PhysicsWorld
from .world_copy import WorldCopy

FOLLOW = dict(distance=1.5, pitch=-30.0)  # the camera behind the car


def moved(last, entry, tol=1e-4):
    """Whether a snapshot entry (key, poses, joint positions) differs from the last one shown."""
    if last is None or last[0] != entry[0] or len(last[1]) != len(entry[1]) or len(last[2]) != len(entry[2]):
        return True
    for (p0, q0), (p1, q1) in zip(last[1], entry[1]):
        if any(abs(a - b) >= tol for a, b in zip(tuple(p0) + tuple(q0), tuple(p1) + tuple(q1))):
            return True
    return any(abs(a - b) >= tol for a, b in zip(last[2], entry[2]))


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


class XConnectionWatch(object):
    """Hears of the process's X connection breaking (the window closed or killed, the X server gone):
    `fd` becomes readable. Install before the window opens. Xlib calls the handler on the thread that
    found the break (PyBullet's drawing thread), which is then parked: Xlib would exit the process
    when the handler returns."""
    _HANDLER = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p)

    def __init__(self):
        self.fd, self._write_fd = os.pipe()
        self._callback = self._HANDLER(self._on_io_error)  # kept: Xlib holds only the pointer
        x11 = _libx11()
        self.installed = x11 is not None
        if self.installed:
            x11.XSetIOErrorHandler.argtypes = [self._HANDLER]
            x11.XSetIOErrorHandler(self._callback)

    def _on_io_error(self, display):
        os.write(self._write_fd, b'x')
        while True:
            time.sleep(3600)


class Window(object):
    def __init__(self):
        self.world = PhysicsWorld(gui=True)  # PhysicsError if PyBullet cannot open it
        self.copy = WorldCopy(self.world)
        self.shown = {}  # name -> snapshot entry last applied

    def show(self, bodies, names, shot, follow):
        if bodies:
            # Every call into a GUI client waits for its next frame: building the room that way took
            # ~7 s (llvmpipe, niced). With drawing off while bodies are built, it is one frame.
            pb.configureDebugVisualizer(pb.COV_ENABLE_RENDERING, 0, physicsClientId=self.world.client)
            try:
                self.copy.sync(bodies)
            finally:
                pb.configureDebugVisualizer(pb.COV_ENABLE_RENDERING, 1, physicsClientId=self.world.client)
        self.copy.prune(set(names))
        for name in [n for n in self.shown if n not in names]:
            del self.shown[name]
        changed = {name: entry for name, entry in shot.items() if moved(self.shown.get(name), entry)}
        self.copy.pose(changed)
        self.shown.update(changed)
        if follow in changed and follow in self.world.bodies:  # a user may turn the camera while the car stands
            self.world.follow_with_camera(self.world.bodies[follow], **FOLLOW)

    def close(self):
        self.world.close()


# How serve() ended
CLOSED = 'closed'    # the window was closed (its X connection broke)
STOPPED = 'stopped'  # the world server said it shuts down
LOST = 'lost'        # the world server's connection broke without a word


def serve(conn, window, x_fd):
    """Shows every update arriving on `conn` until the window closes (x_fd readable) or the world
    server goes -> (CLOSED | STOPPED | LOST, why)."""
    while True:
        ready = wait([conn, x_fd])
        if x_fd in ready:
            return CLOSED, 'its X connection closed'
        try:
            message = conn.recv()
        except (EOFError, OSError) as err:
            return LOST, 'its connection closed without a word (%s): it crashed or was killed' % type(err).__name__
        if message[0] == 'stop':
            return STOPPED, message[1]
        window.show(*message[1:])
        try:
            conn.send(('shown',))
        except (EOFError, OSError) as err:
            return LOST, 'its connection closed without a word (%s): it crashed or was killed' % type(err).__name__

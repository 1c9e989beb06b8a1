"""The window's process: `python -m racebot_sim_bridge.window.viewer_process FD NODE_NAME`, started by gzclient.py.

No rospy here. PyBullet's GUI client with a world_copy.WorldCopy of the simulated world, talking to
the world server (viewer.AttachedWindows) over FD, the socket gzclient connected. For each update
the server sends, it brings the copy's bodies and poses up to date (only what moved: every call
into the GUI client waits for its next frame), keeps the camera on the car, and answers, which
tells the server it may send the next. Niced by gzclient (it inherits), so that physics and
cameras come first.

How it ends says why, in its exit code (gzclient reads it):
  EXIT_STOPPED  the world server said it shuts down;
  EXIT_LOST     the world server's connection broke without a word;
  EXIT_NO_WINDOW  PyBullet could not open the window (the reason on stderr);
  EXIT_CLOSED   the window was closed: PyBullet's window sets no WM_PROTOCOLS, so a window manager's
                close button kills its X connection (XKillClient), and Xlib ends the process with
                exit(1) from PyBullet's drawing thread, whatever Python is doing;
  EXIT_CRASHED  anything else (the traceback on stderr); killed: the signal.
It also ends with gzclient (child_process.helper_main).
"""
import math
import os
import sys
import traceback

import pybullet as pb

from racebot_sim_bridge.engine.child_process import helper_main
from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.engine.physics_types import PhysicsError
from racebot_sim_bridge.engine.world_copy import WorldCopy

EXIT_STOPPED, EXIT_CLOSED, EXIT_LOST, EXIT_CRASHED, EXIT_NO_WINDOW = 0, 1, 3, 4, 5
FOLLOW = dict(distance=1.5, pitch=-30.0)  # the camera behind the car


def moved(last, entry, tol=1e-4):
    """Whether a snapshot entry (key, poses, joint positions) differs from the last one shown."""
    if last is None or last[0] != entry[0] or len(last[1]) != len(entry[1]) or len(last[2]) != len(entry[2]):
        return True
    for (p0, q0), (p1, q1) in zip(last[1], entry[1]):
        if any(abs(a - b) >= tol for a, b in zip(tuple(p0) + tuple(q0), tuple(p1) + tuple(q1))):
            return True
    return any(abs(a - b) >= tol for a, b in zip(last[2], entry[2]))


class Window:
    def __init__(self):
        self.world = PhysicsWorld(gui=True)  # PhysicsError if PyBullet cannot open it
        self.copy = WorldCopy(self.world)
        self.shown = {}  # name -> snapshot entry last applied

    def show(self, bodies, names, shot, follow):
        if bodies:
            # Every call into a GUI client waits for its next frame: building the room that way took
            # ~7 s (llvmpipe, niced). With drawing off while bodies are built, it is one frame.
            self.world.client.configureDebugVisualizer(pb.COV_ENABLE_RENDERING, 0)
            try:
                self.copy.sync(bodies)
            finally:
                self.world.client.configureDebugVisualizer(pb.COV_ENABLE_RENDERING, 1)
        self.copy.prune(set(names))
        for name in [n for n in self.shown if n not in names]:
            del self.shown[name]
        changed = {name: entry for name, entry in shot.items() if moved(self.shown.get(name), entry)}
        self.copy.pose(changed)
        self.shown.update(changed)
        if follow in changed and follow in self.world.bodies:  # a user may turn the camera while the car stands
            self.follow_with_camera(self.world.bodies[follow], **FOLLOW)

    def follow_with_camera(self, body, distance=1.5, yaw_offset=0.0, pitch=-30.0):
        """Puts the window's camera `distance` behind `body` (a physics.Model), looking down by `pitch` degrees."""
        pos, orn = body.pose()
        yaw = math.degrees(pb.getEulerFromQuaternion(orn)[2]) - 90.0 + yaw_offset
        self.world.client.resetDebugVisualizerCamera(distance, yaw, pitch, pos)

    def close(self):
        self.world.close()


def serve(conn, window):
    """Shows every update arriving on `conn` until the world server goes -> EXIT_STOPPED or EXIT_LOST."""
    while True:
        try:
            message = conn.recv()
            if message[0] == 'stop':
                return EXIT_STOPPED
            window.show(*message[1:])
        except (EOFError, OSError):
            return EXIT_LOST
        try:
            conn.send(('shown',))
        except OSError:
            # The server may have said 'stop' and closed while this update was shown: the answer cannot go
            # (EPIPE), but the stop waits in the socket.
            return EXIT_STOPPED if _stop_waiting(conn) else EXIT_LOST


def _stop_waiting(conn):
    """Whether a 'stop' is among what the closed connection still holds."""
    try:
        while conn.poll(0):
            if conn.recv()[0] == 'stop':
                return True
    except (EOFError, OSError):
        pass
    return False


def window_main(fd, node_name):
    conn = helper_main(fd)
    try:
        try:
            window = Window()
        except PhysicsError as err:
            sys.stderr.write('gzclient: the window could not open: %s\n' % err)
            return EXIT_NO_WINDOW
        return serve(conn, window)  # gzclient said hello for this process when it started it
    except (EOFError, OSError):
        return EXIT_LOST
    except Exception:  # noqa: BLE001 (said, and told apart from a closed window's exit code 1)
        traceback.print_exc()
        return EXIT_CRASHED


if __name__ == '__main__':
    code = window_main(int(sys.argv[1]), sys.argv[2])
    sys.stderr.flush()
    os._exit(code)  # not sys.exit: PyBullet's drawing thread would hold up the interpreter's exit

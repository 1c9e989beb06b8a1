"""The window's process: `python -m racebot_sim_bridge.viewer_process FD` (started by viewer.Viewer).

PyBullet's GUI client with a world_copy.WorldCopy of the simulated world. For each snapshot the
simulator sends, it brings the copy's bodies and poses up to date (only what moved: every call into
the GUI client waits for its next frame), keeps the camera on the car, and answers, which tells the
simulator it may send the next. It runs niced (NICENESS): on a machine without a GPU its drawing
thread would otherwise take the cores physics and cameras need. It exits when asked, when its socket
closes, or when the simulator dies (child_process.helper_main). Closing the window ends it too:
PyBullet's window sets no WM_PROTOCOLS, so a window manager's close button kills its X connection,
and Xlib exits the process.
"""
import os
import sys

import pybullet as pb

from .child_process import helper_main
from .physics import PhysicsError, PhysicsWorld
from .world_copy import WorldCopy

NICENESS = 10
FOLLOW = dict(distance=1.5, pitch=-30.0)  # the camera behind the car


def moved(last, entry, tol=1e-4):
    """Whether a snapshot entry (key, poses, joint positions) differs from the last one shown."""
    if last is None or last[0] != entry[0] or len(last[1]) != len(entry[1]) or len(last[2]) != len(entry[2]):
        return True
    for (p0, q0), (p1, q1) in zip(last[1], entry[1]):
        if any(abs(a - b) >= tol for a, b in zip(tuple(p0) + tuple(q0), tuple(p1) + tuple(q1))):
            return True
    return any(abs(a - b) >= tol for a, b in zip(last[2], entry[2]))


class Window(object):
    def __init__(self):
        self.world = PhysicsWorld(gui=True)  # PhysicsError without a display
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


def viewer_main(fd):
    conn = helper_main(fd)
    try:
        os.nice(NICENESS)
    except OSError:
        pass
    conn.recv()  # ('init',)
    try:
        window = Window()
    except PhysicsError as err:
        conn.send(('error', str(err)))
        return
    conn.send(('ready', os.getpid()))
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            return
        if message[0] == 'stop':
            return
        window.show(*message[1:])
        conn.send(('shown',))


if __name__ == '__main__':
    viewer_main(int(sys.argv[1]))

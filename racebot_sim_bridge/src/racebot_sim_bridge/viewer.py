"""Our gzclient: PyBullet's window, in a process of its own, showing a copy of the simulated world.

No rospy here. Physics always runs in a DIRECT client. A GUI client draws in a thread that never
rests (with software OpenGL it takes most of a core) and every call into it waits on that thread.
Held in the simulator's process, it cost real time (a real-time factor of 0.67 with every sensor
subscribed, on 2 cores), and closing or killing the window killed the simulation. So, as gzclient
is to gzserver, the window is a process of its own (viewer_process, started by child_process),
niced so that physics and cameras come first, holding a world_copy.WorldCopy.

About 30 times a second of wall time the physics thread sends it the world's snapshot (poses and
joint positions, a few kB), but only once the window has applied the previous one: the physics never
waits for the window, and a slow window shows fewer updates, never old ones. If the window goes away
(closed, killed, the X server gone), `sync` says why once and returns False; the simulation goes on.
"""
from . import child_process
from .physics import PhysicsError
from .world_copy import snapshot, sources

SYNC_PERIOD = 1.0 / 30  # wall seconds between window updates
START_TIMEOUT = 60.0    # s for the window to open (software OpenGL on a loaded machine is slow)
MODULE = 'racebot_sim_bridge.viewer_process'


class Viewer(object):
    def __init__(self, world, start_timeout=START_TIMEOUT):
        """world: the simulated physics.PhysicsWorld. Raises PhysicsError when the window does not open
        (no display, no OpenGL), saying why."""
        self.world = world
        self.process, self._conn = child_process.start(MODULE)
        self._known = {}      # name -> key of the bodies the window has been sent
        self._busy = False    # a snapshot is on its way or being applied
        self.gone = None      # why the window went away
        try:
            self._conn.send(('init',))
            if not self._conn.poll(start_timeout):
                raise PhysicsError('the window did not open within %g s' % start_timeout)
            reply = self._conn.recv()
        except (EOFError, OSError):
            self.close()
            raise PhysicsError('the window process exited (code %s) before it opened' % self.process.poll())
        except PhysicsError:
            self.close()
            raise
        if reply[0] != 'ready':
            self.close()
            raise PhysicsError(reply[1])

    @property
    def pid(self):
        return self.process.pid

    def sync(self):
        """Sends the window the simulated state, unless it is still applying the last one; call with
        the simulation's lock held. False once the window has gone (see `gone`)."""
        if self.gone is not None:
            return False
        try:
            if self._busy:
                if not self._conn.poll(0):
                    return True
                self._conn.recv()
                self._busy = False
            world = self.world
            bodies = {name: entry for name, entry in sources(world).items() if self._known.get(name) != entry[0]}
            follow = next((name for name, body in world.bodies.items() if body.kind == 'urdf'), None)
            self._conn.send(('sync', bodies, list(world.bodies), snapshot(world), follow))
        except (EOFError, OSError) as err:
            child_process.stop(self.process, self._conn, wait=2.0)
            self.gone = 'the window closed (process %d, exit code %s; %s)' % (
                self.process.pid, self.process.returncode, type(err).__name__)
            return False
        self._busy = True
        for name, (key, _) in bodies.items():
            self._known[name] = key
        return True

    def close(self):
        """Closes the window and waits for its process."""
        if self.gone is None:
            child_process.ask_to_stop(self.process, self._conn)
        child_process.stop(self.process, self._conn)

"""The world server's attach point for windows (our gzclient, gzclient.py): as gzclient is to gzserver.

No rospy here. Physics always runs in a DIRECT client; a window is PyBullet's GUI client in a
process of its own (`rosrun gazebo_ros gzclient`), holding a world_copy.WorldCopy of the world. A
GUI client draws in a thread that never rests (with software OpenGL it takes most of a core), so
held in the world server's process it cost real time, and closing it killed the simulation.

`AttachedWindows` listens on a Unix socket in a private directory (mode 0700: only this user's
processes can attach; the messages are pickles). The world server publishes its path as the
parameter `~gzclient_address`. Any number of windows may attach, each at any time. About 30 times a
second of wall time the physics thread sends each window the bodies it has not seen (their
`Model.source`), the names of all bodies (so deleted ones go) and the world's snapshot (poses and
joint positions, a few kB), but only once that window has applied the previous one, written by a
thread per window: the physics never waits for a window, and a slow window shows fewer updates,
never old ones. A window that goes
away (closed, killed, its X server gone) is forgotten, said once; the simulation goes on.

Protocol (multiprocessing.connection messages): window -> server ('hello', pid, node name) (gzclient sends it
for the window's process as it starts it, before the window opens its GUI), then ('shown',) after each update;
server -> window ('sync', bodies, names, snapshot, follow) and, when the server shuts down, ('stop', why).
"""
import os
import select
import shutil
import socket
import tempfile
import threading
import time
from multiprocessing.connection import Connection

from racebot_sim_bridge.engine.physics_types import BodyKind
from racebot_sim_bridge.engine.world_copy import snapshot, sources

SYNC_PERIOD = 1.0 / 30  # wall seconds between window updates
HELLO_TIMEOUT = 10.0    # s for a connection to say who it is, or it is dropped
ACCEPT_POLL = 0.5       # s between checks of the accept thread for close()
SOCKET_NAME = 'gzclient.sock'


def follow_target(world):
    """The body the window's camera follows: the first robot spawned (URDF), as racebot's window did."""
    return next((name for name, body in world.bodies.items() if body.kind is BodyKind.URDF), None)


class WindowLink:
    """One attached window, seen from the physics thread. Updates are written by a thread of its own:
    a first update holding many bodies may be larger than the socket's buffer, and a window that
    does not read (stopped in a debugger, frozen) must not hold up the physics thread."""

    def __init__(self, sock, now):
        self._sock = sock      # kept to shut down: that wakes the writer out of a blocked send
        self.conn = Connection(os.dup(sock.fileno()))
        self.accepted = now
        self.pid = None        # from its hello
        self.name = None
        self.gone = None       # why it went away
        self._known = {}       # name -> key of the bodies it has been sent
        self._busy = False     # an update is on its way or being applied
        self._outbox = None    # the message for the writer; one at a time (see ready)
        self._closing = False
        self._writer_done = False
        self._send_error = None
        self._cv = threading.Condition()
        self._writer = threading.Thread(target=self._write_loop, name='gzclient-writer', daemon=True)
        self._writer.start()

    def _write_loop(self):
        try:
            while True:
                with self._cv:
                    while self._outbox is None and not self._closing:
                        self._cv.wait()
                    if self._closing:
                        return
                    message, self._outbox = self._outbox, None
                try:
                    self.conn.send(message)
                except (EOFError, OSError) as err:
                    self._send_error = type(err).__name__
                    return
                if message[0] == 'stop':
                    return
        finally:
            # Whoever is last closes the descriptors (never one still in use: no reuse under a send)
            with self._cv:
                self._writer_done = True
                closing = self._closing
            if closing:
                self._close_handles()

    def _post(self, message):
        with self._cv:
            self._outbox = message
            self._cv.notify()

    @property
    def attached(self):
        return self.pid is not None and self.gone is None

    def describe(self):
        return '%s (process %s)' % (self.name or 'a window', self.pid if self.pid is not None else '?')

    def poll_hello(self, now):
        """Reads the window's hello when it has come, without waiting. False when the connection is
        not a window, or said nothing in HELLO_TIMEOUT s (see `gone`)."""
        try:
            if not self.conn.poll(0):
                if now - self.accepted > HELLO_TIMEOUT:
                    return self._lost('it did not say hello within %g s' % HELLO_TIMEOUT)
                return True
            message = self.conn.recv()
        except (EOFError, OSError) as err:
            return self._lost('its connection closed before it said hello (%s)' % type(err).__name__)
        except Exception as err:  # noqa: BLE001 (a malformed pickle from a stranger must not stop the world)
            return self._lost('it sent something unreadable (%s)' % err)
        if not (isinstance(message, tuple) and len(message) == 3 and message[0] == 'hello'):
            return self._lost('its first message was not a hello')
        self.pid, self.name = message[1], str(message[2])
        return True

    def ready(self):
        """Whether it has applied the last update (and so may be sent the next). False when it has
        gone (see `gone`)."""
        if self._send_error is not None:
            self._lost('its connection closed (%s)' % self._send_error)
            return False
        if not self._busy:
            return True
        try:
            if not self.conn.poll(0):
                return False
            self.conn.recv()  # ('shown',)
        except (EOFError, OSError) as err:
            self._lost('its connection closed (%s)' % type(err).__name__)
            return False
        self._busy = False
        return True

    def send(self, all_sources, names, shot, follow):
        """Sends one update: the bodies it has not seen, every name, the snapshot."""
        new = {name: entry for name, entry in all_sources.items() if self._known.get(name) != entry[0]}
        self._post(('sync', new, names, shot, follow))
        self._busy = True
        for name, (key, _) in new.items():
            self._known[name] = key
        return True

    def stop(self, why, wait=1.0):
        """Tells the window the world server is going (it closes; given `wait` s to be told) and drops
        the connection. At shutdown only: it waits."""
        if self.gone is None:
            self._post(('stop', why))
            self._writer.join(wait)
        self.close()

    def close(self):
        """Drops the connection without waiting (the writer, if blocked in a send, is woken and
        closes the descriptors when it ends)."""
        with self._cv:
            self._closing = True
            self._cv.notify()
            writer_done = self._writer_done
        try:
            self._sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        if writer_done:
            self._close_handles()

    def _close_handles(self):
        for closable in (self.conn, self._sock):
            try:
                closable.close()
            except OSError:
                pass

    def _lost(self, why):
        self.gone = why
        self.close()
        return False


class AttachedWindows:
    """The windows attached to one world, and the socket they attach through (see the module doc)."""

    def __init__(self, world, log):
        """world: the simulated physics.PhysicsWorld; log: .info/.warn(message)."""
        self.world = world
        self.log = log
        self._dir = tempfile.mkdtemp(prefix='racebot_gazebo_')  # 0700
        self.address = os.path.join(self._dir, SOCKET_NAME)
        self._listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self._listener.bind(self.address)
        self._listener.listen(8)
        self._new = []                 # accepted connections, handed to the physics thread
        self._new_lock = threading.Lock()
        self._closing = threading.Event()
        self.links = []                # WindowLink, physics thread only
        self._thread = threading.Thread(target=self._accept_loop, name='gzclient-accept', daemon=True)
        self._thread.start()

    @property
    def count(self):
        """How many windows are attached (said hello and still there)."""
        return sum(1 for link in self.links if link.attached)

    def _accept_loop(self):
        # select with a timeout: close() on a socket does not wake a thread blocked in accept()
        while not self._closing.is_set():
            try:
                ready, _, _ = select.select([self._listener], [], [], ACCEPT_POLL)
                if not ready:
                    continue
                sock, _ = self._listener.accept()
            except (OSError, ValueError):
                if self._closing.is_set():
                    return
                time.sleep(ACCEPT_POLL)  # e.g. out of file descriptors: try again later
                continue
            sock.setblocking(True)  # whatever socket.setdefaulttimeout says (rospy sets one)
            with self._new_lock:
                self._new.append(sock)

    def sync(self, now=None):
        """Called by the physics thread with the simulation's lock held, every SYNC_PERIOD: takes in
        new windows, forgets gone ones, sends an update to each that is ready. Never waits for a
        window."""
        now = time.monotonic() if now is None else now
        with self._new_lock:
            new, self._new = self._new, []
        self.links.extend(WindowLink(sock, now) for sock in new)
        update = None
        for link in list(self.links):
            if link.pid is None:
                if not link.poll_hello(now):
                    self._forget(link)
                    continue
                if link.pid is None:
                    continue
                self.log.info('a window attached: %s' % link.describe())
            if not link.ready():
                if link.gone is not None:
                    self._forget(link)
                continue
            if update is None:  # one snapshot for every window ready this round
                world = self.world
                update = (sources(world), list(world.bodies), snapshot(world), follow_target(world))
            if not link.send(*update):
                self._forget(link)

    def _forget(self, link):
        self.links.remove(link)
        if link.pid is not None:
            self.log.warn('the window %s closed (%s): the simulation goes on without it; '
                          '`rosrun gazebo_ros gzclient` opens another' % (link.describe(), link.gone))
        else:
            self.log.warn('dropped a connection to the window socket: %s' % link.gone)

    def close(self, why='it shuts down'):
        """Stops accepting, tells every window why it closes, removes the socket."""
        self._closing.set()
        self._thread.join(2 * ACCEPT_POLL + 1.0)
        try:
            self._listener.close()
        except OSError:
            pass
        with self._new_lock:
            new, self._new = self._new, []
        # connections accepted since the last sync are windows too (one that connected just now): told as well
        now = time.monotonic()
        for link in self.links + [WindowLink(sock, now) for sock in new]:
            link.stop(why)
        self.links = []
        shutil.rmtree(self._dir, ignore_errors=True)

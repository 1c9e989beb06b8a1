"""Camera rendering off the physics thread: a worker process with its own copy of the world.

No rospy here. PyBullet calls hold the GIL, so a render thread would still share the physics
thread's core; a process renders on another core. The worker is `python -m ...render_process`,
started by child_process. It holds a DIRECT client with the EGL renderer when that loads (else the
TinyRenderer) and a world_copy.WorldCopy of the simulated world.

One request per due frame, sent from the physics thread under the simulator's lock: the world's
snapshot (world_copy.snapshot: poses of that sim time), the camera's pose, whether depth is wanted,
and the frame buffer to fill. The worker poses its copy, renders and writes rgb (and depth) into
the buffer, a file in /dev/shm mapped by both processes (no 2 MB image through a pipe), and
replies; RenderWorker's reader thread then hands the frame to the request's `done` callback.
A frame is always of the instant it is stamped with; frames the worker cannot take are skipped by
the caller (FrameBuffers busy), never faked.

If the worker dies, RenderWorker logs an error, fails the requests in flight and starts a new
worker (up to MAX_RESTARTS times); after that `alive` is False and the caller renders itself.
"""
import os
import tempfile
import threading
import time

import numpy as np

from racebot_sim_bridge.engine import child_process
from racebot_sim_bridge.engine.world_copy import sources

MAX_RESTARTS = 3
START_TIMEOUT = 60.0  # s: EGL with llvmpipe takes about a second to start; the machine may be loaded
SHM_DIR = '/dev/shm' if os.path.isdir('/dev/shm') else None


def llvmpipe_threads(cpus):
    """Mesa llvmpipe's rasteriser threads (LP_NUM_THREADS; a GPU driver ignores it): every core on two, one core
    left to the physics thread on more (one core: 0, rasterise in the worker's own thread). Measured on 2 cores,
    racebot.launch with every sensor subscribed in real time: 0 threads 23.3 / 19.5 Hz (800 x 800 camera / depth
    camera), 1 thread 24.6 / 19.7, 2 threads 28.7 / 20.0, real time kept in all three (with the shadow-map pass on,
    before egl_shadow_map, 2 threads had cost the physics real time). A niced worker (5) kept real time too but
    got 19.5 / 17.7 Hz: the physics needs ~15 % of a core and gets it at equal priority."""
    if cpus <= 1:
        return '0'
    return str(cpus if cpus == 2 else cpus - 1)


class FrameBuffers:
    """One camera's frame buffers, shared with the worker: `count` slots of rgb + depth."""

    def __init__(self, width, height, count=2):
        self.width, self.height = width, height
        self.rgb_bytes = width * height * 3
        size = self.rgb_bytes + width * height * 4
        fd, self.path = tempfile.mkstemp(prefix='racebot_frames_', dir=SHM_DIR)
        os.ftruncate(fd, size * count)
        os.close(fd)
        self.slot_bytes = size
        self.maps = [view_slot(self.path, i * size, width, height) for i in range(count)]
        for rgb, depth in self.maps:  # resident from the start: memory does not grow when a slot is first used
            rgb.fill(0)
            depth.fill(0.0)
        self.free = list(range(count))
        self.lock = threading.Lock()

    def take(self):
        """A free slot index, or None when all are in use."""
        with self.lock:
            return self.free.pop(0) if self.free else None

    def give_back(self, slot):
        with self.lock:
            if slot not in self.free:
                self.free.append(slot)

    def offset(self, slot):
        return slot * self.slot_bytes

    def close(self):
        """Removes the file; the mappings stay valid for frames still on their way (no error for
        a frame that arrives after its robot was deleted)."""
        try:
            os.unlink(self.path)
        except OSError:
            pass


class InFlight:
    """How many of one camera's frames the worker holds (sent, not answered yet), at most `limit`.
    Taken on the physics thread and given back on the reader thread, so under a lock: a bare
    `count += 1` / `count -= 1` from two threads loses updates (the camera then stalls for good or
    overfills the worker)."""

    def __init__(self, limit):
        self.limit = limit
        self.count = 0
        self._lock = threading.Lock()

    def take(self):
        """True (and counted) when another frame may go to the worker."""
        with self._lock:
            if self.count >= self.limit:
                return False
            self.count += 1
            return True

    def give_back(self):
        with self._lock:
            self.count -= 1


def view_slot(path, offset, width, height):
    """(rgb uint8 view, depth float32 view) of one slot of a frame-buffer file."""
    rgb = np.memmap(path, dtype=np.uint8, mode='r+', offset=offset, shape=(height, width, 3))
    depth = np.memmap(path, dtype=np.float32, mode='r+', offset=offset + width * height * 3, shape=(height, width))
    return rgb, depth


class RenderWorker:
    """The simulator's side of the worker. `submit` from the physics thread; callbacks run on the
    reader thread.

    The two threads meet at one lock, `_lock`: it covers the connection in use, `ready`, the
    requests in flight (`_pending`, `_next_id`) and the bodies the worker has been sent (`_known`).
    `submit` holds it from its `ready` check to its send, and the reader holds it to install a new
    worker, to take a reply's request and to end a worker. So a request is either in `_pending`
    before a worker's end fails what is pending, or refused (`ready` is False by then); and the
    bodies a request leaves out are known to the very worker it goes to. Callbacks run outside it
    (they publish, and the physics thread holds the simulator's lock while it waits for ours)."""

    def __init__(self, renderer='auto', log=None, on_ready=None):
        """`renderer`: 'auto', 'egl' or 'tiny'; `log`: object with info/warn/error(message);
        `on_ready(description)`: called once the (first) worker runs, with the renderer it uses."""
        self.renderer_choice = renderer
        self.log = log
        self.on_ready = on_ready
        self.alive = True      # False once it died more than MAX_RESTARTS times
        self.ready = False     # a worker is running and answered
        self.renderer = None
        self.description = None
        self.restarts = 0
        self.process = None
        self._conn = None
        self._pending = {}     # request id -> (done, failed, buffers, slot)
        self._next_id = 0
        self._known = {}       # name -> key of the bodies the worker has been sent
        self._lock = threading.Lock()  # see the class docstring
        self._closing = False
        self._lost = None      # why the connection to the last worker ended
        # This thread starts every worker and lives as long as it: the worker's PR_SET_PDEATHSIG
        # fires when the thread that started it ends (and so when the simulator dies).
        self._thread = threading.Thread(target=self._run, name='render_worker', daemon=True)
        self._thread.start()

    # -- physics thread ------------------------------------------------------------------------
    def submit(self, world, shot, camera, position, rotation, want_depth, buffers, slot, done, failed):
        """Queues one frame; False (nothing queued) when no worker is ready. `world`: the simulated
        physics.PhysicsWorld (its bodies are sent to the worker when new); `shot`: world_copy.snapshot;
        `camera`: (width, height, hfov, near, far, noise mean, noise stddev or None);
        `done(rgb, depth or None)` / `failed(reason)` are called once, on the reader thread."""
        with self._lock:
            if not self.ready or self._closing:
                return False
            bodies = {name: entry for name, entry in sources(world).items() if self._known.get(name) != entry[0]}
            request_id = self._next_id
            self._next_id += 1
            message = ('render', request_id, bodies, list(world.bodies), shot, camera, tuple(position),
                       np.asarray(rotation).tolist(), bool(want_depth), buffers.path, buffers.offset(slot))
            try:
                self._conn.send(message)
            except (OSError, EOFError) as err:  # the worker died; the reader sees it too and restarts it
                self.ready = False
                error = err
            else:
                self._pending[request_id] = (done, failed, buffers, slot)
                for name, (key, _) in bodies.items():
                    self._known[name] = key
                return True
        if self.log:
            self.log.error('render worker: could not send a frame request (%s)' % error)
        return False

    # -- reader thread -------------------------------------------------------------------------
    def _run(self):
        while not self._closing:
            try:
                self._start()
            except Exception as err:  # could not even start: count it as a death
                if self.log:
                    self.log.error('render worker: could not start: %s' % err)
                self._stop_process()
                if not self._died():
                    return
                continue
            self._read()
            self._fail_pending('the render worker stopped')
            if self._closing:
                return
            code = self.process.poll() if self.process else None
            if self.log:
                self.log.error('render worker (pid %s) died (exit code %s; %s)' % (
                    self.process.pid if self.process else '?', code, self._lost))
            self._stop_process()
            if not self._died():
                return

    def _died(self):
        """Counts a death; True when another start is allowed."""
        self.restarts += 1
        if self.restarts > MAX_RESTARTS:
            self.alive = False
            if self.log:
                self.log.error('render worker: gave up after %d restarts; cameras render in the physics '
                               'thread (TinyRenderer) from now on' % MAX_RESTARTS)
            return False
        if self.log:
            self.log.warn('render worker: restarting (%d of %d)' % (self.restarts, MAX_RESTARTS))
        time.sleep(0.5)
        return True

    def _start(self):
        process, conn = child_process.start(
            'racebot_sim_bridge.sensors.render_process',
            env={'LP_NUM_THREADS': os.environ.get('LP_NUM_THREADS', llvmpipe_threads(os.cpu_count() or 2))})
        with self._lock:  # nobody sends while ready is False, so the handshake has the connection alone
            self.process, self._conn = process, conn
        conn.send(('init', self.renderer_choice))
        if not conn.poll(START_TIMEOUT):
            raise RuntimeError('no answer within %g s' % START_TIMEOUT)
        kind, renderer, description = conn.recv()
        if kind != 'ready':
            raise RuntimeError(description)
        with self._lock:
            self.renderer, self.description = renderer, description
            self._known = {}  # a new worker has been sent no body
            self.ready = not self._closing
        if self.on_ready:
            self.on_ready('%s (worker pid %d)' % (description, self.process.pid))

    def _read(self):
        while True:
            try:
                reply = self._conn.recv()
            except (EOFError, OSError) as err:
                self._lost = '%s: %s' % (type(err).__name__, err) if str(err) else 'its socket closed'
                return
            _, request_id, error, has_depth = reply
            with self._lock:
                entry = self._pending.pop(request_id, None)
            if entry is None:
                continue
            done, failed, buffers, slot = entry
            try:
                if error:
                    failed(error)
                else:
                    rgb, depth = buffers.maps[slot]
                    done(rgb, depth if has_depth else None)
            except Exception as err:  # a broken callback must not stop the reader
                if self.log:
                    self.log.error('render worker: frame handler failed: %s: %s' % (type(err).__name__, err))

    def _fail_pending(self, reason):
        """Ends the current worker's requests: no request is accepted until the next `_start`."""
        with self._lock:
            self.ready = False
            pending, self._pending = self._pending, {}
        for _, failed, _, _ in pending.values():
            try:
                failed(reason)
            except Exception:
                pass

    def _stop_process(self):
        with self._lock:  # ready is False: submit no longer touches the connection
            self.ready = False
            process, conn = self.process, self._conn
        child_process.stop(process, conn)

    def close(self):
        """Stops the worker and waits for it."""
        with self._lock:
            self._closing = True
            self.ready = False
        child_process.ask_to_stop(self.process, self._conn, lock=self._lock)
        self._thread.join(2.0)  # the worker exits, the reader sees its socket close and ends
        self._stop_process()    # (closing a connection the reader still reads would raise there)
        self._thread.join(2.0)
        self._fail_pending('the render worker was closed')

"""Races where the physics thread and the render worker's reader thread meet (render_worker.py,
gazebo_plugins/gazebo_ros_camera.py), provoked: many thousand request/reply cycles with the two threads forced to switch
between any two bytecodes of the code under test (interleaved(): an opcode trace function is a
Python call, so with a 1 us switch interval the GIL can change hands before every instruction).

No master, no worker process: the worker's side is a thread behind a real socket pair."""
import contextlib
import queue
import threading
import time
import types
from multiprocessing.connection import Pipe

import numpy as np
import pytest

from racebot_sim_bridge.gazebo_plugins import gazebo_ros_camera
from racebot_sim_bridge.sensors import render_worker
from racebot_sim_bridge.sensors.frame_publisher import FramePublisher
from racebot_sim_bridge.sensors.schedule import RateMeter

from interleaving import interleaved

WAIT = 120.0  # wall seconds without progress before a test gives up (a hang; a slow shared machine only takes longer)
pytestmark = pytest.mark.filterwarnings("error::pytest.PytestUnhandledThreadExceptionWarning")  # a crashed reader fails


class Stalled:
    """True once `count()` has not grown for WAIT wall seconds. The cycles are counted, not timed: under the opcode
    switching a loaded 2-core machine takes minutes for what a quiet one does in seconds, and only no progress at
    all is a hang."""

    def __init__(self, count):
        self.count, self.last, self.since = count, count(), time.monotonic()

    def __call__(self):
        now, value = time.monotonic(), self.count()
        if value != self.last:
            self.last, self.since = value, now
        return now - self.since > WAIT


# -- render_worker.RenderWorker: submit on the physics thread, replies and restarts on the reader --

class FakeWorkerProcess:
    """The render process's side, a thread: answers 'init', then each frame request, and dies
    (closes its end) after `lifetime` requests, so that the reader fails what is pending and
    starts another. A request naming a body this incarnation was never sent is answered with an
    error: the frame would lack that body."""
    pid = 4242

    def __init__(self, conn, lifetime, log):
        self.conn, self.lifetime, self.log = conn, lifetime, log
        self.thread = threading.Thread(target=self.serve, daemon=True)
        self.thread.start()

    def serve(self):
        try:
            if self.conn.recv()[0] != 'init':  # asked to stop while starting
                return
            self.conn.send(('ready', 'tiny', 'fake renderer'))
            known = set()
            for _ in range(self.lifetime):
                message = self.conn.recv()
                if message[0] == 'stop':
                    return
                _, request_id, bodies, names = message[:4]
                known.update(bodies)
                missing = [n for n in names if n not in known]
                self.conn.send(('frame', request_id, 'never sent: %s' % missing if missing else None, False))
                if missing:
                    self.log.append(missing)
        except (EOFError, OSError):
            pass
        finally:
            self.conn.close()

    def poll(self):
        return None if self.thread.is_alive() else 0

    def wait(self, timeout=None):
        self.thread.join(timeout)


def fake_child_process(lifetimes, log):
    def start(module, env=None):
        ours, theirs = Pipe()
        return FakeWorkerProcess(theirs, next(lifetimes), log), ours

    def stop(process, conn, wait=5.0):
        conn.close()

    def ask_to_stop(process, conn, wait=2.0, lock=None):
        with lock or contextlib.nullcontext():
            try:
                conn.send(('stop',))
            except OSError:
                pass
    return types.SimpleNamespace(start=start, stop=stop, ask_to_stop=ask_to_stop)


class FakeBuffers:
    path = '/nonexistent'
    maps = [(None, None)]

    def offset(self, slot):
        return 0


def test_every_accepted_frame_request_gets_one_reply_across_restarts(monkeypatch):
    requests = 5000
    rng = np.random.default_rng(18)
    lifetimes = iter(int(n) for n in rng.integers(1, 40, size=10 ** 5))
    missing = []
    monkeypatch.setattr(render_worker, 'child_process', fake_child_process(lifetimes, missing))
    monkeypatch.setattr(render_worker, 'MAX_RESTARTS', 10 ** 6)
    monkeypatch.setattr(render_worker, 'time', types.SimpleNamespace(sleep=lambda s: None))
    bodies = {'car': (1, 'car source'), 'ground': (2, 'ground source')}
    monkeypatch.setattr(render_worker, 'sources', lambda world: bodies)
    world = types.SimpleNamespace(bodies=dict.fromkeys(bodies))
    replies = {}  # request number -> replies received
    raised = []   # what submit raised (it must not: the physics thread would stop)
    lock = threading.Lock()

    def reply_to(number):
        def reply(*_):
            with lock:
                replies[number] += 1
        return reply
    with interleaved(render_worker):
        worker = render_worker.RenderWorker('tiny')
        accepted = 0
        stalled = Stalled(lambda: accepted)
        while accepted < requests and not stalled() and worker._thread.is_alive():
            with lock:
                replies[accepted] = 0
            try:
                sent = worker.submit(world, None, (4, 4), (0, 0, 0), np.eye(3), False, FakeBuffers(), 0,
                                     reply_to(accepted), reply_to(accepted))
            except Exception as err:
                raised.append('%s: %s' % (type(err).__name__, err))
                continue
            if sent:
                accepted += 1
        worker.close()
    with lock:
        lost = [n for n in range(accepted) if replies[n] == 0]
        twice = [n for n in range(accepted) if replies[n] > 1]
    problems = []
    if raised:
        problems.append('submit raised %d times, first: %s' % (len(raised), raised[0]))
    if accepted < requests:
        problems.append('only %d of %d requests accepted (reader thread alive: %s)' % (
            accepted, requests, worker._thread.is_alive()))
    if lost:
        problems.append('%d accepted requests never got a reply' % len(lost))
    if twice:
        problems.append('%d requests got more than one reply' % len(twice))
    if missing:
        problems.append('%d frames requested of a worker never sent their bodies' % len(missing))
    assert not problems, '; '.join(problems)


# -- gazebo_ros_camera.CameraSensor: its count of frames in the worker, on both threads --------------------

class FakeWorker:
    """Takes frame requests on the physics thread; a reader thread answers them (every fifth one
    fails). Records the most requests it ever held at once."""

    def __init__(self):
        self.ready = True
        self.queue = queue.Queue()
        self.lock = threading.Lock()
        self.held = 0
        self.most_held = 0
        self.submitted = 0
        self.answering = threading.Event()
        self.answering.set()
        self.thread = threading.Thread(target=self.answer, daemon=True)

    def submit(self, world, shot, camera, position, rotation, want_depth, buffers, slot, done, failed):
        with self.lock:
            self.held += 1
            self.submitted += 1
            self.most_held = max(self.most_held, self.held)
        self.queue.put((done, failed, self.submitted))
        return True

    def answer(self):
        while True:
            item = self.queue.get()
            if item is None:
                return
            self.answering.wait()
            done, failed, number = item
            with self.lock:
                self.held -= 1
            if number % 5:
                done(None, None)
            else:
                failed('a failed frame')
            self.queue.task_done()


def camera_sensor(worker):
    manager = types.SimpleNamespace(worker=worker, worker_expected=lambda: True, snapshot=lambda: None,
                                    frame_failed=lambda sensor, reason: None)
    sensor = gazebo_ros_camera.CameraSensor.__new__(gazebo_ros_camera.CameraSensor)  # no ROS: only what capture() uses
    sensor.__dict__.update(manager=manager, sim=types.SimpleNamespace(world=None), meter=RateMeter(),
                           mount=types.SimpleNamespace(pose=lambda: (np.zeros(3), (0.0, 0.0, 0.0, 1.0))),
                           camera=types.SimpleNamespace(width=4, height=4), worker_camera=(4, 4),
                           publishers={}, failed=False, buffers=None,
                           in_worker=render_worker.InFlight(gazebo_ros_camera.FRAMES_IN_WORKER),
                           publisher=FramePublisher('camera'))
    return sensor


def test_frames_in_the_worker_are_counted_right_from_both_threads():
    worker = FakeWorker()
    sensor = camera_sensor(worker)
    try:
        with interleaved(gazebo_ros_camera):
            worker.thread.start()
            stalled = Stalled(lambda: worker.submitted)
            while worker.submitted < 20000 and not stalled():
                sensor.capture(0.0, None, {'image'}, False)
            worker.queue.join()
            # and published: each answered frame keeps its buffer until the camera's own publisher thread has run
            # it, which a loaded machine may not have done yet (a capture then finds no free buffer, not a full
            # worker); that thread runs its jobs in order, so one more job done means the frames' are
            published = threading.Event()
            sensor.publisher.run(published.set)
            assert published.wait(WAIT), 'the camera\'s publisher thread did not run its frames'
        assert worker.submitted == 20000, 'the camera stopped sending frames after %d' % worker.submitted
        assert worker.most_held <= gazebo_ros_camera.FRAMES_IN_WORKER, (
            'the worker held %d frames at once' % worker.most_held)
        # All answered: the camera may again have FRAMES_IN_WORKER frames in the worker.
        worker.answering.clear()
        before = worker.submitted
        for _ in range(gazebo_ros_camera.FRAMES_IN_WORKER + 1):
            sensor.capture(0.0, None, {'image'}, False)
        assert worker.submitted - before == gazebo_ros_camera.FRAMES_IN_WORKER
    finally:
        worker.answering.set()
        worker.queue.put(None)
        if sensor.buffers is not None:
            sensor.buffers.close()

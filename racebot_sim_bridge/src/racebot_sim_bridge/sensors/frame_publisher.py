"""One camera's frames handed from the render worker's reader thread to a thread of the camera's own.

The reader thread reads every camera's replies in turn. When it also built and published each frame, a camera's
reply waited behind another camera's publishing (a depth camera's point cloud: ~20 ms of wall time in a busy world
server) and its frames stayed counted in the worker meanwhile, so the camera's next due frames were skipped
(measured: 800 x 800 camera 22.6 of 30 Hz, 6-8 frames skipped a second, with the worker 65 % busy). Now the reader
only hands a frame over: each camera publishes in order on its own thread, and one camera's publishing never
delays another's frames. No rospy here: jobs are plain callables.
"""
import collections
import threading


class FramePublisher:
    """Runs jobs in the order given, on one daemon thread started with the first job."""

    def __init__(self, name, log_error=None):
        self.name = name
        self.log_error = log_error  # log_error(message), or None
        self._jobs = collections.deque()
        self._cond = threading.Condition()
        self._thread = None
        self._closed = False

    def run(self, job, cancel=None):
        """Queues `job()`; `cancel()` is called instead when the publisher is (or gets) closed before it runs.
        Returns False (and cancels) when closed."""
        with self._cond:
            if not self._closed:
                self._jobs.append((job, cancel))
                if self._thread is None:
                    self._thread = threading.Thread(target=self._loop, name=self.name, daemon=True)
                    self._thread.start()
                self._cond.notify()
                return True
        if cancel is not None:
            cancel()
        return False

    def _loop(self):
        while True:
            with self._cond:
                self._cond.wait_for(lambda: self._jobs or self._closed)
                if not self._jobs:
                    return
                job, _ = self._jobs.popleft()
            try:
                job()
            except Exception as err:  # a broken frame must not stop the camera's later frames
                if self.log_error:
                    self.log_error('%s: %s: %s' % (self.name, type(err).__name__, err))

    def close(self):
        """Cancels the jobs not started and lets the thread end after the one running."""
        with self._cond:
            self._closed = True
            jobs, self._jobs = list(self._jobs), collections.deque()
            self._cond.notify_all()
        for _, cancel in jobs:
            if cancel is not None:
                try:
                    cancel()
                except Exception:
                    pass

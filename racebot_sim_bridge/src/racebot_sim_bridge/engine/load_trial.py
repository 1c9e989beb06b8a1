"""A URDF is loaded in a helper process before the live world loads it: whatever PyBullet does with a
description (crash the process, spin for half an hour), it does it there, and the spawn is refused with what
happened while the world server steps on (issue 29 item 2: no description may take the world down).

The known causes are fixed where the URDF is written (engine/bullet_urdf.py); this guard is for those not
known yet. The helper (`python -m racebot_sim_bridge.engine.load_trial FD`, started at the first check and
again after it died) has a DIRECT PyBullet of its own: it loads the file with the live world's flags and
removes it, so a check costs one more load of the same file. No rospy here.
"""
from __future__ import annotations

import signal
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from multiprocessing.connection import Connection

from racebot_sim_bridge.engine import child_process

# Wall seconds a load may take in the helper before the spawn is refused: the slowest real robot here (a
# mobile manipulator with its meshes) loads in under 2 s on this 2-core machine; a load that spins is
# one of hours.
DEFAULT_TIMEOUT = 60.0
HELPER_EXIT_WAIT = 10.0  # s for a helper that hung up to be reaped (a crash may write a core dump first)


class LoadTrial:
    """check(path, ...) loads the URDF at `path` in the helper: None when the process came through it (loaded,
    or refused with a PyBullet error, which the live load raises the same), else what happened to it."""

    def __init__(self, timeout: float = DEFAULT_TIMEOUT) -> None:
        self.timeout = timeout
        self.process: subprocess.Popen | None = None
        self.conn: Connection | None = None
        # The helper dies with the thread that started it (PR_SET_PDEATHSIG), and checks run in rospy's
        # service threads, which end with their call: helpers are started by this one thread, which lives on.
        self._starter = ThreadPoolExecutor(max_workers=1, thread_name_prefix='load_trial')

    def check(self, path: str, flags: int, fixed: bool) -> str | None:
        if self.process is None or self.process.poll() is not None:
            self._restart()
        try:
            self.conn.send(('load', path, flags, fixed))
            if not self.conn.poll(self.timeout):  # still loading: it may never end
                self._stop()
                return 'PyBullet did not finish loading it in %g s' % self.timeout
            self.conn.recv()
            return None
        except (OSError, EOFError):
            pass  # the helper's end of the connection closed: it died while loading
        try:
            code = self.process.wait(HELPER_EXIT_WAIT)
        except subprocess.TimeoutExpired:
            code = None
        self._stop()
        return 'PyBullet crashed loading it (%s)' % ('its process hung up' if code is None else _death(code))

    def _restart(self) -> None:
        self._stop()
        start = self._starter.submit(child_process.start, 'racebot_sim_bridge.engine.load_trial')
        self.process, self.conn = start.result()

    def _stop(self) -> None:
        child_process.stop(self.process, self.conn, wait=1.0)
        self.process = self.conn = None

    def close(self) -> None:
        child_process.ask_to_stop(self.process, self.conn, wait=1.0)
        self._stop()
        self._starter.shutdown(wait=False)


def _death(code: int) -> str:
    """subprocess's returncode as words: a signal by its name, else the exit status."""
    if code < 0:
        try:
            return 'killed by %s' % signal.Signals(-code).name
        except ValueError:
            return 'killed by signal %d' % -code
    return 'exit status %d' % code


def main(fd: int) -> None:
    """The helper: loads each file it is sent and answers 'ok' or PyBullet's error, until ('stop',)."""
    conn = child_process.helper_main(fd)
    import pybullet as pb
    client = pb.connect(pb.DIRECT)
    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):
            return
        if job[0] != 'load':
            return
        _, path, flags, fixed = job
        try:
            body = pb.loadURDF(path, flags=flags, useFixedBase=fixed, physicsClientId=client)
        except pb.error as err:
            conn.send(str(err))
            continue
        pb.removeBody(body, physicsClientId=client)
        conn.send('ok')


if __name__ == '__main__':
    main(int(sys.argv[1]))

"""When sensors update, how often they really did, and how much wall time rendering may take.

Pure Python: no rospy, no pybullet.
- UpdateSchedule: a sensor's update times in sim time at its declared rate, without drift
  (30 Hz on a 1 ms step gives updates 33 or 34 ms apart, 30 per simulated second).
- RateMeter: counts published updates and measures them against sim time and wall time.
- RenderBudget: a token bucket over wall time. Rendering on a CPU is slow (an 800 x 800 frame
  takes ~0.1 s); with a budget share s < 1, frames are rendered only while rendering has used
  at most s of the wall time, and due frames beyond that are skipped (counted, never faked).
  The physics keeps its pace and the camera's achieved rate drops, as a Gazebo camera's does on
  a slow machine. s >= 1 renders every due frame, slowing the whole simulation instead.
"""
import math
import threading

TIME_EPS = 1e-9


class UpdateSchedule:
    def __init__(self, rate, start=0.0):
        """`rate` Hz of sim time (0 or less: every world update); first update due at `start`."""
        self.period = 1.0 / rate if rate and rate > 0 and math.isfinite(rate) else 0.0
        self.next = start
        self.last = None

    def due(self, time):
        """True when an update is due at sim `time`. A reset that sends time back restarts the
        schedule from there."""
        if self.last is not None and time < self.last - TIME_EPS:
            self.next = time
            self.last = None
        return time >= self.next - TIME_EPS

    def advance(self, time):
        """Marks the update due at `time` as done (or skipped) and schedules the next one."""
        self.last = time
        if self.period <= 0.0:
            self.next = time
            return
        self.next += self.period
        if self.next <= time + TIME_EPS:  # fell more than a period behind: no burst to catch up
            self.next = time + self.period


class RateMeter:
    """Counts events between `snapshot` calls; rates over sim time and wall time.

    Thread-safe: a camera ticks on the render worker's reader thread, other sensors tick and skip
    on the physics thread, snapshots come from the diagnostics timer. `+=` is a read and a write
    that another thread may come between (a lost count), and a snapshot must read the counts once
    (or the ticks in between are counted in two snapshots): all under one lock.
    `frames`: the events are a camera's frames, whose wall rate Gazebo also reports as the sensor's fps."""

    def __init__(self, frames=False):
        self.frames = frames
        self.count = 0
        self.skipped = 0
        self.total = 0
        self._since = None  # (sim time, wall time, count, skipped) at the last snapshot
        self._lock = threading.Lock()

    def tick(self):
        with self._lock:
            self.count += 1
            self.total += 1

    def skip(self):
        with self._lock:
            self.skipped += 1

    def snapshot(self, sim_time, wall_time):
        """(sim Hz, wall Hz, skipped) since the previous snapshot; None for the first call or
        when no sim time has passed."""
        with self._lock:
            count, skipped = self.count, self.skipped
            previous = self._since
            self._since = (sim_time, wall_time, count, skipped)
        if previous is None:
            return None
        sim0, wall0, count0, skipped0 = previous
        dsim, dwall = sim_time - sim0, wall_time - wall0
        if dsim <= 0.0 or dwall <= 0.0:
            return None
        return (count - count0) / dsim, (count - count0) / dwall, skipped - skipped0


class RenderBudget:
    """Shared by all rendering sensors. Fair: when credit is available, a sensor whose frames
    were skipped longest ago goes first (the others skip until it has rendered), so a 30 Hz and
    a 20 Hz camera both get frames instead of the faster one taking them all."""
    STALE = 1.0  # wall seconds after which a waiting sensor that stopped asking is forgotten

    def __init__(self, share, clock, burst=0.3):
        """`share`: the fraction of wall time rendering may use (>= 1: no limit); `clock()`:
        wall seconds; `burst`: how many seconds of rendering credit may build up."""
        self.share = float(share)
        self.clock = clock
        self.burst = float(burst)
        self.credit = self.burst
        self.last = clock()
        self.waiting = {}  # sensor -> [wall time of its first skipped frame, wall time it last asked]

    @property
    def unlimited(self):
        return self.share >= 1.0

    def allow(self, who=None):
        """True when `who` may render a frame now; False means skip this frame."""
        if self.unlimited:
            return True
        now = self.clock()
        self.credit = min(self.burst, self.credit + (now - self.last) * self.share)
        self.last = now
        for other in [w for w, (_, asked) in self.waiting.items() if now - asked > self.STALE]:
            del self.waiting[other]  # no longer due (nobody listens to it any more)
        mine = self.waiting.get(who)
        first = mine[0] if mine else now
        if self.credit > 0.0 and not any(since < first for w, (since, _) in self.waiting.items() if w is not who):
            self.waiting.pop(who, None)
            return True
        self.waiting[who] = [first, now]
        return False

    def spend(self, seconds):
        """Charges the wall time a render took."""
        if not self.unlimited:
            self.credit -= seconds


class FrameThrottle:
    """A gazebo_ros plugin's own updateRate on top of its sensor's updates: an update is passed on
    when at least 1 / rate of sim time has gone by since the last one passed, else dropped whole
    (a 20 Hz sensor under a 15 Hz plugin rate publishes every other update: 10 Hz), as
    gazebo_ros_range and gazebo_ros_camera_utils compare `now - last_update_time >= update_period`.
    A rate of 0 (or less) passes every update. Time going back (a reset) starts over."""

    def __init__(self, rate):
        self.period = 1.0 / rate if rate and rate > 0 and math.isfinite(rate) else 0.0
        self.last = None

    def passes(self, time):
        if self.last is not None and time < self.last - TIME_EPS:
            self.last = None
        if self.last is not None and time - self.last < self.period - TIME_EPS:
            return False
        self.last = time
        return True

"""When a gazebo_plugins model plugin updates: the clocks of their UpdateChild, on Gazebo's time.

Gazebo's common::Time counts whole nanoseconds, so times here are integer nanoseconds: with float
seconds, 0.011 - 0.001 > 0.01 may hold or not. Three habits are found upstream:
- FixedPeriod (skid_steer_drive, joint_state_publisher): update when more than one period has passed,
  then move the last update time on by exactly one period (100 Hz at a 1 ms step: every 10 ms).
- SincePublished (planar_move's odometry): update when more than one period has passed since the last
  update, which becomes now (20 Hz at 1 ms: every 51 ms, 19.6 Hz).
- AtLeastPeriod (p3d): update when at least one period has passed; the last time becomes now.
A rate <= 0 means every world update. Time going backwards (reset_simulation) restarts the clock at
the new time, as p3d and joint_state_publisher do (skid_steer_drive and planar_move would wait until
the old time came round again).
"""
from racebot_sim_bridge.engine.sim_time import NS, to_ns


class _Clock:
    def __init__(self, rate, start):
        self.period = 1.0 / rate if rate > 0 else 0.0
        self.last = to_ns(start)
        # A plugin's shortcut at every world update: while 0 <= now - last < quiet_ns (integer ns), no update
        # is due; from quiet_ns on, one is. 0 for every world update, when the range is empty.
        self.quiet_ns = self._first_due_gap()

    def _passed(self, since):
        """Whether an update is due `since` seconds after the last: more than one period has passed."""
        return since > self.period

    def _first_due_gap(self):
        """The least gap (integer ns) since the last update at which _passed holds, as the clock computes the
        seconds since ((gap) / 1e9, a float); 0 for a period of 0 (every update)."""
        if self.period <= 0:
            return 0
        gap = to_ns(self.period)
        while gap > 0 and self._passed((gap - 1) / float(NS)):
            gap -= 1
        while not self._passed(gap / float(NS)):
            gap += 1
        return gap

    def quiet(self, now):
        """True when surely no update is due at `now` (integer ns): the caller need not ask."""
        return 0 <= now - self.last < self.quiet_ns

    def quiet_span(self):
        """[from, until) in integer ns in which quiet() holds: a plugin's ModelPlugin.quiet_span."""
        return self.last, self.last + self.quiet_ns

    def _since(self, now):
        if now < self.last:
            self.last = now
        return (now - self.last) / float(NS)


class FixedPeriod(_Clock):
    def due(self, time):
        now = to_ns(time)
        if self._passed(self._since(now)):
            self.last += to_ns(self.period)
            return True
        return False


class SincePublished(_Clock):
    def due(self, time):
        """(due, seconds since the last update)"""
        now = to_ns(time)
        since = self._since(now)
        if self._passed(since):
            self.last = now
            return True, since
        return False, since


class AtLeastPeriod(_Clock):
    def _passed(self, since):
        """At least one period has passed."""
        return since >= self.period

    def since(self, time):
        """Seconds since the last update when one is due, else None; call mark(time) when it is made."""
        since = self._since(to_ns(time))
        return since if self._passed(since) else None

    def mark(self, time):
        self.last = to_ns(time)


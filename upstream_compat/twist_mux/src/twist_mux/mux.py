"""twist_mux's rule, free of ROS: which velocity topic a message may pass from, given every topic's and lock's
last message time. As upstream 3.1.3 (topic_handle.h, twist_mux.cpp): priorities clamped to 0..255; a handle has
expired when its timeout is > 0 and its last message is older than that (never received counts as time 0); a
lock is locked when expired or its last Bool is true; the lock priority is the highest of the locked locks (0:
none); a velocity topic is masked when expired or below the lock priority; a message passes when its topic is the
first, among the unmasked, with the highest priority (above 0)."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass
class Handle:
    name: str
    topic: str
    timeout: float
    priority: int
    stamp: float = 0.0
    data: bool = False  # a lock's last std_msgs/Bool

    def __post_init__(self):
        self.priority = min(max(int(self.priority), 0), 255)

    def expired(self, now: float) -> bool:
        return self.timeout > 0.0 and now - self.stamp > self.timeout


def handles(entries, what) -> list[Handle]:
    """Handles from the ~topics or ~locks parameter: a list of {name, topic, timeout, priority}. ValueError
    naming what is wrong (upstream: "Error parsing params", and it runs without them)."""
    if entries is None:
        return []
    if not isinstance(entries, list):
        raise ValueError('~%s must be a list of {name, topic, timeout, priority}, got %r' % (what, entries))
    out = []
    for i, e in enumerate(entries):
        if not isinstance(e, dict) or any(k not in e for k in ('name', 'topic', 'timeout', 'priority')):
            raise ValueError('~%s[%d] needs name, topic, timeout and priority, got %r' % (what, i, e))
        out.append(Handle(str(e['name']), str(e['topic']), float(e['timeout']), int(e['priority'])))
    return out


def lock_priority(locks: list[Handle], now: float) -> int:
    return max([lock.priority for lock in locks if lock.expired(now) or lock.data], default=0)


def has_priority(topic: Handle, topics: list[Handle], locks: list[Handle], now: float) -> bool:
    """Whether a message that just arrived on `topic` (its stamp already set to `now`) is relayed."""
    floor = lock_priority(locks, now)
    best, winner = 0, None
    for h in topics:
        if not (h.expired(now) or h.priority < floor) and best < h.priority:
            best, winner = h.priority, h.name
    return topic.name == winner

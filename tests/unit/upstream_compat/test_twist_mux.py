"""upstream_compat/twist_mux (reduced): upstream 3.1.3's rule for which velocity topic is relayed, with
ridgeback_control's twist_mux.yaml shape (joystick over interactive marker over external cmd_vel, an e_stop
lock of timeout 0). No ROS master."""
import pytest

from twist_mux.mux import Handle, handles, has_priority, lock_priority

TOPICS = [{'name': 'joy', 'topic': 'joy_teleop/cmd_vel', 'timeout': 0.5, 'priority': 10},
          {'name': 'interactive_marker', 'topic': 'twist_marker_server/cmd_vel', 'timeout': 0.5, 'priority': 8},
          {'name': 'external', 'topic': 'cmd_vel', 'timeout': 0.5, 'priority': 1}]
LOCKS = [{'name': 'e_stop', 'topic': 'e_stop', 'timeout': 0.0, 'priority': 255}]


def receive(h, now):
    h.stamp = now
    return h


def test_external_cmd_vel_passes_when_nothing_else_talks():
    topics, locks = handles(TOPICS, 'topics'), handles(LOCKS, 'locks')
    external = topics[2]
    assert has_priority(receive(external, 100.0), topics, locks, 100.0)


def test_a_higher_priority_topic_masks_a_lower_one_until_it_times_out():
    topics, locks = handles(TOPICS, 'topics'), handles(LOCKS, 'locks')
    joy, _, external = topics
    receive(joy, 100.0)
    assert not has_priority(receive(external, 100.2), topics, locks, 100.2)
    assert has_priority(receive(external, 100.6), topics, locks, 100.6)  # joy older than its 0.5 s


def test_a_held_lock_masks_lower_topics_and_a_timeout_0_lock_never_expires():
    topics, locks = handles(TOPICS, 'topics'), handles(LOCKS, 'locks')
    e_stop = locks[0]
    assert lock_priority(locks, 1000.0) == 0  # timeout 0: never expired, and not held
    e_stop.data = True
    assert lock_priority(locks, 1000.0) == 255
    assert not has_priority(receive(topics[0], 1000.0), topics, locks, 1000.0)


def test_a_lock_with_a_timeout_locks_when_silent():
    topics = handles(TOPICS, 'topics')
    locks = [Handle('pause', 'pause', 1.0, 100)]
    assert lock_priority(locks, 5.0) == 100  # never received: expired
    receive(locks[0], 5.0)
    assert lock_priority(locks, 5.5) == 0
    assert not has_priority(receive(topics[2], 7.0), topics, locks, 7.0)  # priority 1 < 100


def test_priorities_clamped_and_bad_params_named():
    assert Handle('x', 'x', 0.0, 900).priority == 255
    with pytest.raises(ValueError, match=r'~topics\[0\] needs'):
        handles([{'name': 'x'}], 'topics')
    assert handles(None, 'locks') == []

"""keyboard_teleop's key logic (racebot_gazebo.teleop_keys), on a fake clock: no Tk, no rospy."""
import heapq
import itertools

import pytest

from racebot_gazebo import teleop_keys
from racebot_gazebo.teleop_keys import STOP, DriveCommand, KeyState, TeleopController

SPEED, STEER = 0.5, 0.34


class FakeUI:
    """The UI interface of TeleopController on a virtual clock."""

    def __init__(self):
        self.now = 0.0
        self.queue = []  # (time, seq, fn)
        self.cancelled = set()
        self.seq = itertools.count()
        self.closed = False

    def schedule(self, delay, fn):
        handle = next(self.seq)
        heapq.heappush(self.queue, (self.now + delay, handle, fn))
        return handle

    def cancel(self, handle):
        self.cancelled.add(handle)

    def close(self):
        self.closed = True

    def advance(self, seconds):
        end = self.now + seconds
        while self.queue and self.queue[0][0] <= end + 1e-9:
            t, handle, fn = heapq.heappop(self.queue)
            if handle in self.cancelled:
                continue
            self.now = t
            fn()
        self.now = end


@pytest.fixture
def rig():
    ui = FakeUI()
    sent = []  # (time, command)
    ctl = TeleopController(KeyState(SPEED, STEER), ui, lambda c: sent.append((ui.now, c)), period=0.1)
    return ui, ctl, sent


# -- KeyState -------------------------------------------------------------------------------------
def test_no_key_no_command():
    assert KeyState().command() is None


def test_defaults_are_the_original_yaml():
    k = KeyState()
    assert (k.speed, k.max_steering_angle) == (0.5, 0.34)


def test_w_then_s_latest_wins_and_release_gives_the_other_back():
    k = KeyState(SPEED, STEER)
    assert k.press('w') and k.command() == DriveCommand(SPEED, 0.0)
    assert k.press('s') and k.command() == DriveCommand(-SPEED, 0.0)
    assert k.release('s') and k.command() == DriveCommand(SPEED, 0.0)  # W is still held
    assert k.release('w') and k.command() is None


def test_a_d_exclusive_left_is_positive():
    k = KeyState(SPEED, STEER)
    k.press('a')
    assert k.command() == DriveCommand(0.0, STEER)
    k.press('d')
    assert k.command() == DriveCommand(0.0, -STEER)
    k.press('w')
    assert k.command() == DriveCommand(SPEED, -STEER)
    k.release('d')
    assert k.command() == DriveCommand(SPEED, STEER)


def test_other_keys_and_repeated_presses_change_nothing():
    k = KeyState()
    assert not k.press('x') and not k.release('x') and k.command() is None
    k.press('w')
    assert not k.press('w') and not k.release('s')


def test_q_requests_quit():
    k = KeyState()
    assert k.press('q') and k.quit_requested


@pytest.mark.parametrize('keysym, char, key', [('w', 'w', 'w'), ('W', 'W', 'w'), ('D', '', 'd'),
                                               ('Q', 'Q', 'q'), ('Up', '', None), ('x', 'x', None)])
def test_normalize_key(keysym, char, key):
    assert teleop_keys.normalize_key(keysym, char) == key


@pytest.mark.parametrize('bad', [-1.0, float('nan'), float('inf'), 'fast', True])
def test_bad_parameters_rejected(bad):
    with pytest.raises(ValueError):
        KeyState(speed=bad)
    with pytest.raises(ValueError):
        KeyState(max_steering_angle=bad)


# -- TeleopController -----------------------------------------------------------------------------
def test_hold_w_publishes_at_once_then_every_period(rig):
    ui, ctl, sent = rig
    ctl.key_pressed('w')
    ui.advance(1.0)
    assert [c for _, c in sent] == [DriveCommand(SPEED, 0.0)] * 11
    assert [round(t, 6) for t, _ in sent] == [round(0.1 * i, 6) for i in range(11)]


def test_release_all_sends_one_stop_then_silence(rig):
    ui, ctl, sent = rig
    ctl.key_pressed('w')
    ui.advance(0.45)
    ctl.key_pressed('a')
    ui.advance(0.2)
    assert sent[-1][1] == DriveCommand(SPEED, STEER)
    ctl.key_released('w')
    ui.advance(0.2)
    assert sent[-1][1] == DriveCommand(0.0, STEER)
    n = len(sent)
    ctl.key_released('a')
    ui.advance(5.0)
    tail = [c for _, c in sent[n:]]
    # at most one period's command still due inside the auto-repeat window, then one stop, then nothing
    assert tail[-1] == STOP and tail.count(STOP) == 1 and len(tail) <= 2, tail
    assert set(tail[:-1]) <= {DriveCommand(0.0, STEER)}
    assert sent[-1][0] == pytest.approx(0.85 + teleop_keys.DEFAULT_REPEAT_WINDOW)


def test_nothing_published_without_keys(rig):
    ui, ctl, sent = rig
    ctl.key_released('w')
    ctl.key_pressed('x')
    ui.advance(2.0)
    assert sent == []


def test_auto_repeat_pairs_are_not_releases(rig):
    """X auto-repeat: KeyRelease + KeyPress of the held key together, every 33 ms."""
    ui, ctl, sent = rig
    ctl.key_pressed('w')
    for _ in range(30):
        ui.advance(0.033)
        ctl.key_released('w')
        ctl.key_pressed('w')
    ui.advance(0.001)
    assert STOP not in [c for _, c in sent]
    assert len(sent) == 10  # still 10 Hz: the pairs neither stop nor restart the period
    ctl.key_released('w')
    ui.advance(1.0)
    assert [c for _, c in sent].count(STOP) == 1


def test_w_then_s_through_the_controller(rig):
    ui, ctl, sent = rig
    ctl.key_pressed('w')
    ui.advance(0.25)
    ctl.key_pressed('s')
    assert sent[-1] == (0.25, DriveCommand(-SPEED, 0.0))  # at once, not at the next period
    ctl.key_released('s')
    ui.advance(0.1)
    assert sent[-1][1] == DriveCommand(SPEED, 0.0)


def test_q_stops_a_moving_car_and_closes(rig):
    ui, ctl, sent = rig
    ctl.key_pressed('w')
    ui.advance(0.3)
    ctl.key_pressed('q')
    assert ui.closed and sent[-1][1] == STOP
    n = len(sent)
    ui.advance(1.0)
    ctl.key_pressed('w')
    ui.advance(1.0)
    assert len(sent) == n


def test_q_when_stopped_sends_nothing(rig):
    ui, ctl, sent = rig
    ctl.key_pressed('q')
    assert ui.closed and sent == []


def test_focus_lost_stops_the_car(rig):
    ui, ctl, sent = rig
    ctl.key_pressed('w')
    ui.advance(0.3)
    ctl.focus_lost()
    n = len(sent)
    ui.advance(1.0)
    assert sent[-1][1] == STOP and len(sent) == n

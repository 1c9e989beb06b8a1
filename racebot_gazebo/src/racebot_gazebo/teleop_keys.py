"""Keys -> drive commands: the keyboard teleop's logic, with no rospy and no Tk (unit-testable).

`KeyState` knows which drive keys are held and what command they mean. `TeleopController` joins a
`KeyState` to a UI and to a publish function and decides *when* to publish:

- while a drive key is held: a command at once, then one every `period` seconds (the UI's clock);
- when the last drive key is released: exactly one stop command (speed 0, steering 0), then nothing,
  so the car does not run away on the last command (the tutorial's node left it driving);
- Q: one stop if a command is still in force, then the UI is closed;
- a release followed within `repeat_window` seconds by a press of the same key is X's key
  auto-repeat (Tk sees KeyRelease/KeyPress pairs while a key is held with repeat on), not a release.

The UI is any object with `schedule(delay_s, fn) -> handle`, `cancel(handle)` and `close()`; the Tk
window implements it with `after()`, the unit tests with a fake clock.
"""
import collections
import math

FORWARD, BACKWARD, LEFT, RIGHT, QUIT = 'w', 's', 'a', 'd', 'q'
DRIVE_KEYS = (FORWARD, BACKWARD, LEFT, RIGHT)
# Keys that cancel each other: of a held pair, the one pressed last wins.
OPPOSITE = {FORWARD: BACKWARD, BACKWARD: FORWARD, LEFT: RIGHT, RIGHT: LEFT}

DEFAULT_SPEED = 0.5               # m/s, the original project's keyboard_teleop.yaml
DEFAULT_MAX_STEERING_ANGLE = 0.34  # rad, idem (the hinge limit is 0.6)
DEFAULT_PERIOD = 0.1              # s between commands while a key is held (the tutorial's 10 Hz)
DEFAULT_REPEAT_WINDOW = 0.03      # s; X auto-repeat's release/press pairs arrive together

DriveCommand = collections.namedtuple('DriveCommand', 'speed steering_angle')
STOP = DriveCommand(0.0, 0.0)


def normalize_key(keysym, char=''):
    """Tk's keysym/char of an event -> one of 'w', 'a', 's', 'd', 'q', or None (other keys).

    Upper case counts (Caps Lock, Shift), as the tutorial's `e.char == c or e.keysym == c` intends."""
    for name in (keysym, char):
        if name and len(name) == 1:
            name = name.lower()
            if name in DRIVE_KEYS or name == QUIT:
                return name
    return None


class KeyState:
    """Which drive keys are held, in the order they were pressed, and the command they mean.

    W/S set the speed (+speed / -speed), A/D the steering angle (+max left / -max right, REP 103);
    of W and S (or A and D) held together, the one pressed last counts, and releasing it gives the
    other back. Q sets `quit_requested`."""

    def __init__(self, speed=DEFAULT_SPEED, max_steering_angle=DEFAULT_MAX_STEERING_ANGLE):
        for name, value in (('speed', speed), ('max_steering_angle', max_steering_angle)):
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value) \
                    or value < 0:
                raise ValueError('%s must be a finite number >= 0, got %r' % (name, value))
        self.speed = float(speed)
        self.max_steering_angle = float(max_steering_angle)
        self.held = []  # drive keys, oldest press first
        self.quit_requested = False

    def press(self, key):
        """A key went down; True if that changed the command (or asked to quit)."""
        if key == QUIT:
            self.quit_requested = True
            return True
        if key not in DRIVE_KEYS:
            return False
        before = self.command()
        if key in self.held:
            self.held.remove(key)
        self.held.append(key)
        return self.command() != before

    def release(self, key):
        """A key went up; True if that changed the command."""
        if key not in self.held:
            return False
        before = self.command()
        self.held.remove(key)
        return self.command() != before

    def release_all(self):
        """Forget every held key (the window lost the focus, so their releases will not come)."""
        changed = bool(self.held)
        del self.held[:]
        return changed

    def _latest(self, a, b):
        for key in reversed(self.held):
            if key in (a, b):
                return key
        return None

    def command(self):
        """The DriveCommand of the held keys, or None when no drive key is held."""
        if not self.held:
            return None
        speed = {FORWARD: self.speed, BACKWARD: -self.speed, None: 0.0}[self._latest(FORWARD, BACKWARD)]
        steer = {LEFT: self.max_steering_angle, RIGHT: -self.max_steering_angle,
                 None: 0.0}[self._latest(LEFT, RIGHT)]
        return DriveCommand(speed, steer)


class TeleopController:
    """Publishes the commands of a KeyState on a UI's clock (see the module docstring)."""

    def __init__(self, keys, ui, publish, period=DEFAULT_PERIOD, repeat_window=DEFAULT_REPEAT_WINDOW):
        if not period > 0:
            raise ValueError('period must be > 0, got %r' % (period,))
        self.keys = keys
        self.ui = ui
        self.publish = publish
        self.period = float(period)
        self.repeat_window = max(0.0, float(repeat_window))
        self._tick_handle = None
        self._pending_release = {}  # key -> UI handle of the deferred release
        self._stop_owed = False     # a command other than STOP is in force
        self._closed = False

    # -- UI events --------------------------------------------------------------------------------
    def key_pressed(self, key):
        if self._closed:
            return
        if key == QUIT:
            self.keys.press(QUIT)
            self.shutdown()
            self.ui.close()
            return
        handle = self._pending_release.pop(key, None)
        if handle is not None:  # a release/press pair of auto-repeat: the key never went up
            self.ui.cancel(handle)
            return
        if self.keys.press(key):
            self._publish_now()

    def key_released(self, key):
        if self._closed or key not in self.keys.held or key in self._pending_release:
            return
        if self.repeat_window == 0:
            self._commit_release(key)
        else:
            self._pending_release[key] = self.ui.schedule(self.repeat_window,
                                                          lambda: self._commit_release(key))

    def focus_lost(self):
        """The window lost the keyboard: the held keys' releases will go elsewhere, so stop now."""
        if self._closed:
            return
        self._cancel_pending_releases()
        if self.keys.release_all():
            self._publish_now()

    def shutdown(self):
        """Stops all timers; publishes one stop if a drive command is still in force. Idempotent."""
        if self._closed:
            return
        self._closed = True
        self._cancel_pending_releases()
        if self._tick_handle is not None:
            self.ui.cancel(self._tick_handle)
            self._tick_handle = None
        self.keys.release_all()
        if self._stop_owed:
            self._stop_owed = False
            self.publish(STOP)

    # -- internals --------------------------------------------------------------------------------
    def _cancel_pending_releases(self):
        for handle in self._pending_release.values():
            self.ui.cancel(handle)
        self._pending_release.clear()

    def _commit_release(self, key):
        self._pending_release.pop(key, None)
        if self.keys.release(key):
            self._publish_now()

    def _publish_now(self):
        """The command changed: publish it at once and restart the period from here."""
        if self._tick_handle is not None:
            self.ui.cancel(self._tick_handle)
            self._tick_handle = None
        self._tick()

    def _tick(self):
        self._tick_handle = None
        if self._closed:
            return
        command = self.keys.command()
        if command is None:
            if self._stop_owed:  # every key is up: one stop, then silence
                self._stop_owed = False
                self.publish(STOP)
            return
        self.publish(command)
        self._stop_owed = command != STOP
        self._tick_handle = self.ui.schedule(self.period, self._tick)

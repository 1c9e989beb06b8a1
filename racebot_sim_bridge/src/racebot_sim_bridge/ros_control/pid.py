"""A PID controller with control_toolbox's (ROS 1, Noetic) semantics.

Pure Python: no rospy. Each PID command controller (``controller_interface.PidCommandController``, behind
ros_controllers' effort and velocity controllers) owns one ``Pid``.

Semantics (read from control_toolbox ``src/pid.cpp``, noetic-devel):

- The integral state is the integral of the error, ``i_error += dt * error``.
- Without antiwindup the integral *term* ``i * i_error`` is clamped to
  ``[i_clamp_min, i_clamp_max]``; the integral state itself keeps growing.  So with
  ``i_clamp`` 0 (the default) the integral term is always 0, whatever ``i`` is.
- With antiwindup (and ``i != 0``) the integral *state* is clamped to
  ``[i_clamp_min / i, i_clamp_max / i]`` (bounds sorted), and the term is not clamped again.
- ``error_dot`` is ``(error - previous error) / dt``.

Where this class differs from control_toolbox, on purpose (the project's contract; tests/unit/ros_control/test_pid.py
holds it):

- No derivative on the first update after construction or ``reset()``: control_toolbox
  starts with a previous error of 0 and so kicks ``d * error / dt`` on that update.
- ``dt <= 0`` (not only ``dt == 0``), a non-finite ``dt`` or a non-finite error returns
  0.0 and leaves every piece of state untouched (control_toolbox's two-argument form
  already stores the error before it bails out).
- Finite inputs give a finite command: a term that overflows (an error or gain near the
  float range) saturates at the largest float, where control_toolbox would give inf or NaN.
"""

import math
import sys

__all__ = ['Pid']

# Keys control_toolbox's Pid::init() reads from the parameter server.
_PARAM_KEYS = ('p', 'i', 'd', 'i_clamp', 'i_clamp_min', 'i_clamp_max', 'antiwindup')


_INF = float('inf')
_MAX = sys.float_info.max


def _is_number(value):
    """True for int/float values (bool excluded: YAML ``true`` is not a gain)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _gain(value, name):
    """``value`` as a finite float, else ``ValueError`` naming ``name``."""
    if not _is_number(value) or not math.isfinite(value):
        raise ValueError('%s must be a finite number, got %r' % (name, value))
    return float(value)


def _clamp(value, low, high):
    return max(low, min(value, high))


class Pid:
    """Proportional-integral-derivative controller on an error signal.

    ``compute(error, dt)`` returns ``p*e + i_term + d*de/dt``; see the module docstring for
    the clamping rules.  The last errors and terms are kept for JointControllerState.
    When built (CMakeLists.txt), pid.pxd compiles this class with typed fields: each effort
    controller computes it every update.
    """

    def __init__(self, p, i=0.0, d=0.0, i_clamp_min=0.0, i_clamp_max=0.0, antiwindup=False):
        self.set_gains(p, i, d, i_clamp_min, i_clamp_max, antiwindup)
        self.reset()

    @classmethod
    def from_params(cls, params, where='pid'):
        """Build a ``Pid`` from a ``pid`` parameter dictionary, as ``Pid::init()`` does.

        ``where`` is the parameter namespace used in error messages, e.g.
        ``/racebot/left_rear_wheel_velocity_controller/pid``.

        Only ``p`` is required; ``i`` and ``d`` default to 0.  ``i_clamp`` sets the bounds to
        ``-|i_clamp| .. +|i_clamp|``; ``i_clamp_min`` / ``i_clamp_max``, when present,
        override the respective bound (as ``-|x|`` and ``+|x|``: the minimum is never above 0
        and the maximum never below 0).  ``antiwindup`` defaults to false.
        """
        if not isinstance(params, dict):
            raise ValueError('%s: no PID gains given (got %r); set pid: {p: ...}'
                             % (where, params))
        if 'p' not in params:
            raise ValueError("%s: no 'p' gain given; set pid: {p: ...}" % where)

        def number(key, default=0.0):
            value = params.get(key, default)
            if not _is_number(value) or not math.isfinite(value):
                raise ValueError('%s/%s: expected a finite number, got %r; set e.g. %s: %s'
                                 % (where, key, value, key, default))
            return float(value)

        p = number('p', 1.0)
        i = number('i')
        d = number('d')
        i_clamp = abs(number('i_clamp'))
        i_clamp_min, i_clamp_max = -i_clamp, i_clamp
        if 'i_clamp_min' in params:
            i_clamp_min = -abs(number('i_clamp_min'))
        if 'i_clamp_max' in params:
            i_clamp_max = abs(number('i_clamp_max'))
        antiwindup = params.get('antiwindup', False)
        if not isinstance(antiwindup, bool):
            raise ValueError('%s/antiwindup: expected true or false, got %r'
                             % (where, antiwindup))
        return cls(p, i, d, i_clamp_min, i_clamp_max, antiwindup)

    # -- gains ------------------------------------------------------------------------

    def set_gains(self, p, i=0.0, d=0.0, i_clamp_min=0.0, i_clamp_max=0.0, antiwindup=False):
        """Replace the gains; the controller state is kept (like ``Pid::setGains``)."""
        p, i, d = _gain(p, 'p'), _gain(i, 'i'), _gain(d, 'd')
        i_clamp_min = _gain(i_clamp_min, 'i_clamp_min')
        i_clamp_max = _gain(i_clamp_max, 'i_clamp_max')
        if i_clamp_min > i_clamp_max:
            raise ValueError('i_clamp_min (%g) must not be above i_clamp_max (%g)'
                             % (i_clamp_min, i_clamp_max))
        if not isinstance(antiwindup, bool):
            raise ValueError('antiwindup must be True or False, got %r' % (antiwindup,))
        self._p, self._i, self._d = p, i, d
        self._i_min, self._i_max = i_clamp_min, i_clamp_max
        self._antiwindup = antiwindup

    @property
    def p(self):
        return self._p

    @property
    def i(self):
        return self._i

    @property
    def d(self):
        return self._d

    @property
    def i_clamp_min(self):
        return self._i_min

    @property
    def i_clamp_max(self):
        return self._i_max

    @property
    def i_clamp(self):
        """The value JointControllerState reports as ``i_clamp``: the upper bound."""
        return self._i_max

    @property
    def antiwindup(self):
        return self._antiwindup

    # -- state ------------------------------------------------------------------------

    def reset(self):
        """Clear the integral, the errors and the command; the next derivative is 0."""
        self._has_previous = False
        self._previous_error = 0.0
        self._p_error = 0.0
        self._i_error = 0.0
        self._d_error = 0.0
        self._p_term = 0.0
        self._i_term = 0.0
        self._d_term = 0.0
        self._command = 0.0

    @property
    def p_error(self):
        """The error of the last update."""
        return self._p_error

    @property
    def i_error(self):
        """The integral of the error (not multiplied by ``i``), as control_toolbox reports."""
        return self._i_error

    @property
    def d_error(self):
        """The error derivative used by the last update."""
        return self._d_error

    @property
    def p_term(self):
        return self._p_term

    @property
    def i_term(self):
        return self._i_term

    @property
    def d_term(self):
        return self._d_term

    @property
    def command(self):
        """The output of the last successful update (0 after ``reset()``)."""
        return self._command

    # -- update -----------------------------------------------------------------------

    @staticmethod
    def _usable(dt, *values):
        return (_is_number(dt) and math.isfinite(dt) and dt > 0.0
                and all(_is_number(v) and math.isfinite(v) for v in values))

    def compute(self, error, dt):
        """One update with ``error = target - state`` over ``dt`` seconds.

        Returns 0.0, changing nothing, when ``dt <= 0`` or either value is not finite.
        """
        # Fast path for what the controllers pass (two floats, dt > 0, both finite: x - x is nan for
        # inf and nan); anything else takes the full check.
        if not (error.__class__ is float and dt.__class__ is float and 0.0 < dt < _INF and error - error == 0.0) \
                and not self._usable(dt, error):
            return 0.0
        e = float(error)
        error_dot = (e - self._previous_error) / dt if self._has_previous else 0.0
        self._previous_error = e
        self._has_previous = True
        return self._update(e, error_dot, float(dt))

    def compute_with_error_dot(self, error, error_dot, dt):
        """One update with a derivative supplied by the caller (e.g. a velocity error).

        Like control_toolbox, this form does not touch the previous error that
        ``compute`` differentiates against.  Returns 0.0, changing nothing, on bad input.
        """
        if not self._usable(dt, error, error_dot):
            return 0.0
        return self._update(float(error), float(error_dot), float(dt))

    def _update(self, error, error_dot, dt):
        self._p_error = error
        self._d_error = error_dot
        self._p_term = self._p * error

        self._i_error += dt * error
        if self._antiwindup and self._i != 0.0:
            low, high = sorted((self._i_min / self._i, self._i_max / self._i))
            self._i_error = _clamp(self._i_error, low, high)
        # i == 0 gives a zero term even if the integral state has overflowed to inf.
        i_term = self._i * self._i_error if self._i != 0.0 else 0.0
        if not self._antiwindup:
            i_term = max(self._i_min, min(i_term, self._i_max))  # _clamp, inlined: every update passes here
        self._i_term = i_term

        self._d_term = self._d * error_dot
        command = self._p_term + self._i_term + self._d_term
        if command - command != 0.0:  # inf or NaN (x - x is 0 for every finite x): terms overflowed
            command = self._saturated()
        self._command = command
        return command

    def _saturated(self):
        """The command with each overflowed term held at the largest float, and the sum saturated too (so
        an overflow to +inf and one to -inf make no NaN)."""
        self._p_term, self._i_term, self._d_term = (_clamp(t, -_MAX, _MAX) if not math.isnan(t) else 0.0
                                                    for t in (self._p_term, self._i_term, self._d_term))
        return _clamp(self._p_term + self._i_term + self._d_term, -_MAX, _MAX)

    def __repr__(self):
        return ('Pid(p=%g, i=%g, d=%g, i_clamp_min=%g, i_clamp_max=%g, antiwindup=%s)'
                % (self._p, self._i, self._d, self._i_min, self._i_max, self._antiwindup))

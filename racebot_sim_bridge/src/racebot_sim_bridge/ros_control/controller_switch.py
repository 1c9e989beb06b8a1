"""switch_controller's checks, as controller_manager 0.20 makes them, and the accepted switch (`SwitchRequest`)
that the controller manager's next update carries out. No ROS: the manager (controller_manager.py) calls
`plan_switch` under its lock with its loaded controllers and their states; every refusal is logged as an error
saying what was wrong and what to do."""
import threading

BEST_EFFORT = 1
STRICT = 2


class SwitchRequest:
    """An accepted switch_controller call, waiting for the update loop (ros_control's realtime side)."""

    def __init__(self, start, stop, start_asap, timeout):
        self.start = start  # loaded controllers' names, as requested (BEST_EFFORT's unknown ones dropped)
        self.stop = stop
        self.start_asap = start_asap
        self.timeout = timeout  # s; bounds the caller's wait (wait_for_switch)
        self.ok = False
        self.done = threading.Event()

    def finish(self, ok):
        self.ok = ok
        self.done.set()

    def cancel(self):
        self.finish(False)


def plan_switch(loaded, state, start, stop, strictness, start_asap, timeout, log):
    """The accepted SwitchRequest, or None when refused (nothing changes). `loaded`: name -> Entry in load
    order; `state`: name -> 'initialized' | 'running' | 'stopped'.

    Unknown names: STRICT refuses, BEST_EFFORT skips them. Then, per loaded controller: stopping one that is
    not running, or starting one that runs (and is not also stopped), is refused under STRICT and dropped from
    the check under BEST_EFFORT; a name left in both lists is refused whatever the strictness. Last, no joint
    may be claimed by two controllers that would run afterwards, whatever the interfaces
    (RobotHW::checkForConflict)."""
    strict = _strictness(strictness, log) == STRICT
    stop_names = _known('stop', stop, loaded, strict, log)
    start_names = None if stop_names is None else _known('start', start, loaded, strict, log)
    if start_names is None:
        return None
    after = _running_after(loaded, state, start_names, stop_names, strict, start_asap, log)
    if after is None:
        return None
    if in_conflict(loaded, after, log):
        log.error('Could not switch controllers, due to resource conflict; stop the controller that holds the '
                  'joint in the same switch')
        return None
    return SwitchRequest(start_names, stop_names, bool(start_asap), timeout)


def _strictness(strictness, log):
    """STRICT or BEST_EFFORT: 0 is BEST_EFFORT with ros_control's warning, any other value BEST_EFFORT too."""
    if strictness == 0:
        log.warn('Controller Manager: To switch controllers you need to specify a strictness level of '
                 'controller_manager_msgs::SwitchController::STRICT (%d) or ::BEST_EFFORT (%d). '
                 'Defaulting to ::BEST_EFFORT.' % (STRICT, BEST_EFFORT))
        return BEST_EFFORT
    if strictness not in (BEST_EFFORT, STRICT):  # ros_control treats these as BEST_EFFORT, silently
        log.warn('Controller Manager: strictness %d is neither STRICT (%d) nor BEST_EFFORT (%d); '
                 'it is treated as BEST_EFFORT' % (strictness, STRICT, BEST_EFFORT))
        return BEST_EFFORT
    return strictness


def _known(verb, names, loaded, strict, log):
    """The loaded ones of `names` ('stop' or 'start' them), or None when STRICT refuses an unknown one."""
    known = []
    for n in names:
        if n in loaded:
            known.append(n)
            continue
        problem = ("Could not %s controller with name '%s' because no controller with this name exists "
                   "(loaded: %s)" % (verb, n, ', '.join(loaded) or 'none'))
        if strict:
            log.error(problem + '; STRICT switch refused; nothing was changed')
            return None
        log.warn(problem + ' (BEST_EFFORT: skipped)')
    return known


def _running_after(loaded, state, start_names, stop_names, strict, start_asap, log):
    """The controllers that would run after the switch, in load order; None when the switch is refused."""
    after = []
    for n in loaded:
        running = state[n] == 'running'
        in_stop, in_start = n in stop_names, n in start_names
        if not running and in_stop:
            if strict:
                log.error("Could not stop controller '%s' since it is not running; STRICT switch refused; nothing "
                          "was changed" % n)
                return None
            log.warn("Controller '%s' is not running (BEST_EFFORT: not stopped)" % n)
            in_stop = False
        if running and not in_stop and in_start:
            if strict:
                log.error("Controller '%s' is already running; STRICT switch refused; nothing was changed" % n)
                return None
            log.warn("Controller '%s' is already running (BEST_EFFORT: %s)"
                     % (n, 'left running' if start_asap else 'restarted'))
            in_start = False
        if in_stop and in_start:  # "Could no", sic: ros_control 0.20's words
            log.error("Could no start or stop controller '%s' because of conflicting switching command; "
                      "to restart it, stop it in one switch and start it in the next" % n)
            return None
        if (running and not in_stop) or in_start:
            after.append(n)
    return after


def in_conflict(loaded, names, log):
    """RobotHW::checkForConflict: a joint claimed by two of these controllers, through any interfaces."""
    claims = {}
    for n in names:
        for _iface, resources in loaded[n].controller.claimed_resources():
            for r in resources:
                claims.setdefault(r, []).append(n)
    conflicts = sorted((r, who) for r, who in claims.items() if len(who) > 1)
    for r, who in conflicts:
        log.warn('Resource conflict on [%s].  Controllers = [%s, ]' % (r, ', '.join(who)))
    return bool(conflicts)

"""The command path's observer, the hook `make bench` measures command latency through: the command controllers
tell the I/O object's `command_trace` (a `CommandObserver`, None = off: one attribute test per update) when a command
is taken and applied; the world server sets a `CommandTrace` there when its `~command_trace` parameter names a file.
The trace is written in the world server's own process, which the bench starts through the product launch file and
reaches only through that parameter, so it lives here beside the hook, not in tools/bench (which reads the file:
tools/bench/scenarios.py, analyse_trace)."""


class CommandObserver:
    """What a command controller tells an observer of its command path (the I/O object's
    `command_trace`): `command_taken` on the subscriber's thread once a command is in force
    (`received` as published, `kept` after clamping; ignored non-finite commands are not told), and
    `command_applied` on the physics thread after each update, with the command that update used."""

    def command_taken(self, controller, received, kept):
        pass

    def command_applied(self, controller, command):
        pass


class CommandTrace(CommandObserver):
    """Opt-in record of the command path, for measurements (make bench): for every command a
    controller takes, a line `arrived <wall time> <controller> <value>`, and `applied <wall time>
    <controller> <value>` after the first update that uses it (a command overtaken by a newer one
    before any update is never applied). Wall time is time.monotonic() (CLOCK_MONOTONIC, comparable
    across processes on one machine)."""

    def __init__(self, path, clock=None):
        import threading
        import time
        self.clock = clock or time.monotonic
        self._file = open(path, 'a', buffering=1)  # line-buffered: a reader sees whole lines
        self._lock = threading.Lock()
        self._unapplied = {}  # controller -> the last command taken, until an update uses it

    def record(self, event, controller, value, when):
        with self._lock:
            self._file.write('%s %.9f %s %r\n' % (event, when, controller, value))

    def command_taken(self, controller, received, kept):
        when = self.clock()
        with self._lock:
            self._unapplied[controller] = kept
        self.record('arrived', controller.param_ns, received, when)

    def command_applied(self, controller, command):
        # Compared with the value, not a flag: an update that read the command just before a new
        # one was taken applied the old one, and the new one is still to be applied.
        with self._lock:
            if controller not in self._unapplied or self._unapplied[controller] != command:
                return
            del self._unapplied[controller]
        self.record('applied', controller.param_ns, command, self.clock())

    def close(self):
        self._file.close()

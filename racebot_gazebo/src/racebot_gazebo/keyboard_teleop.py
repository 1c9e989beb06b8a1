"""keyboard_teleop: drive the racebot with W/A/S/D from a small Tk window (the tutorial's node, Python 3).

Focus the window, hold W/S to drive forward/back and A/D to steer left/right; Q (or closing the
window) quits. The key logic is racebot_gazebo.teleop_keys; this module is its Tk window and ROS plumbing.

Publishes:
  /ackermann_cmd_mux/output (ackermann_msgs/AckermannDriveStamped): at once when a key goes down,
      then every 1/~rate s while a drive key is held; one stop (speed 0, steering 0) when the last
      key goes up, and on exit if a command is still in force.
Parameters (private, read once):
  ~speed (m/s, 0.5)                 speed while W or S is held
  ~max_steering_angle (rad, 0.34)   steering angle while A or D is held
  ~rate (Hz, 10)                    commands per second while a key is held

Timing runs on Tk's after(), i.e. on the wall clock, in the Tk thread, not on a rospy.Timer:
- a keyboard is a human interface: "every 0.1 s while held" is wall time. Under /use_sim_time a
  rospy.Timer runs on /clock, so before the simulator publishes /clock, or while it is paused, it
  would never fire (a key would do nothing, and a release would send no stop), and at a real-time
  factor other than 1 the rate would follow the simulator, not the hand;
- key events and publishing happen in one thread, so a stop can never be overtaken by a stale drive
  command from a timer thread, and no lock is needed.

Under a bare X server (no window manager) the window opens beside the 3D window, not under it, and
moves beside a 3D window that opens over it later (window_place).

The user's X key auto-repeat is left alone (the tutorial's node ran `xset r off`, a setting of the
whole X session that a hard kill left off). A held key's auto-repeat reaches Tk as KeyRelease +
KeyPress pairs sent together; teleop_keys.TeleopController takes a release followed at once by a
press of the same key for what it is, the key still held.
Without a display the node prints one line and exits with status 0, so a headless launch goes on.
"""
import math
import os
import signal
import sys
import time
import traceback

from . import teleop_keys, window_place

TOPIC = '/ackermann_cmd_mux/output'
WINDOW_TITLE = 'racebot keyboard teleop'
HELP_TEXT = 'Focus on this window\nand use the WASD keys\nto drive the car.\n\nPress Q to quit'
POLL_PERIOD = 0.1        # s; how often the Tk loop looks for signals and a rospy shutdown
FOCUS_CHECK_DELAY = 0.05  # s after a FocusOut before deciding the window has lost the keyboard
STOP_FLUSH_TIME = 0.3     # s given to the final stop command to leave before the node shuts down
LOOK_PERIOD = 0.5         # s between looks for a 3D window over this one (no window manager only)


def say(line):
    """One line on stdout, flushed (roslaunch shows it with output="screen")."""
    sys.stdout.write('keyboard_teleop: %s\n' % line)
    sys.stdout.flush()


class TkWindow:
    """The Tk window: the UI of a TeleopController (schedule/cancel/close on Tk's after())."""

    def __init__(self, tkinter):
        self.tk = tkinter
        self.root = tkinter.Tk()  # raises TclError when the display cannot be opened
        self.root.title(WINDOW_TITLE)
        self.frame = tkinter.Frame(self.root, width=100, height=100)
        self.frame.pack()
        tkinter.Label(self.frame, height=10, width=30, text=HELP_TEXT).pack()
        self.frame.focus_set()
        self.root.protocol('WM_DELETE_WINDOW', lambda: self.close('window closed'))
        self.close_reason = None
        self._should_stop = lambda: None
        self._windows = None      # window_place.TopWindows while we look for the 3D window
        self._seen = set()        # 3D windows already looked at: each moves this one at most once
        self._asked = None        # (x, y) last asked for

    # -- the UI interface of TeleopController -----------------------------------------------------
    def schedule(self, delay, fn):
        return self.root.after(max(1, int(round(delay * 1000.0))), fn)

    def cancel(self, handle):
        try:
            self.root.after_cancel(handle)
        except self.tk.TclError:  # the window is already gone (destroyed from outside)
            pass

    def close(self, reason='Q pressed'):
        if self.close_reason is None:
            self.close_reason = reason
        self.root.quit()  # mainloop() returns; the window is destroyed by destroy()

    # -- place on the screen ----------------------------------------------------------------------
    def keep_beside_the_3d_window(self):
        """Before the window shows: beside the 3D window if it is there; then, every LOOK_PERIOD, beside
        a 3D window that opens over it. Not under a window manager, which places windows itself."""
        try:
            self._windows = window_place.TopWindows()
        except OSError:
            return
        self.root.withdraw()  # sized, not shown yet
        self.root.update_idletasks()
        self._look()
        self.root.deiconify()

    def _reparented(self):
        """Whether a window manager holds the window in a frame of its own."""
        return int(self.root.wm_frame(), 16) != self.root.winfo_id()

    def _look(self):
        if self._reparented():
            self._windows.close()
            self._windows = None
            return
        root = self.root
        for window, rectangle in self._windows.find().items():
            if window in self._seen:
                continue
            self._seen.add(window)
            size = (root.winfo_reqwidth(), root.winfo_reqheight())
            position = self._asked or (root.winfo_rootx(), root.winfo_rooty())
            if window_place.overlap(position + size, rectangle):
                self._asked = window_place.beside(rectangle, size, (root.winfo_screenwidth(),
                                                                    root.winfo_screenheight()))
                root.geometry('+%d+%d' % self._asked)
                # Moved now, not at idle: the raise's ConfigureNotify (old place), read first, would undo it
                root.update_idletasks()
                root.lift()
        self.schedule(LOOK_PERIOD, self._look)

    # -- wiring -----------------------------------------------------------------------------------
    def bind(self, controller):
        def key(handler):
            def on_event(event):
                k = teleop_keys.normalize_key(event.keysym, event.char)
                if k is not None:
                    handler(k)
            return on_event

        # On the toplevel: its bindings see the events of every widget inside it.
        self.root.bind('<KeyPress>', key(controller.key_pressed))
        self.root.bind('<KeyRelease>', key(controller.key_released))

        def focus_check():
            if self.root.focus_get() is None:  # focus left the application, not just moved inside it
                controller.focus_lost()
        self.root.bind('<FocusOut>', lambda _e: self.schedule(FOCUS_CHECK_DELAY, focus_check))

    def run(self, should_stop):
        """mainloop() until close(); `should_stop()` -> reason or None, polled every POLL_PERIOD."""
        def poll():
            reason = should_stop()
            if reason:
                self.close(reason)
            else:
                self.schedule(POLL_PERIOD, poll)
        self.schedule(POLL_PERIOD, poll)
        self.root.mainloop()

    def destroy(self):
        if self._windows is not None:
            self._windows.close()
        try:
            self.root.destroy()
        except self.tk.TclError:
            pass


class KeyboardTeleopNode:
    """The ROS side: parameters, the publisher, and DriveCommand -> AckermannDriveStamped."""

    def __init__(self, rospy, msg_type):
        self.rospy = rospy
        self.msg_type = msg_type
        self.speed = self._param('~speed', teleop_keys.DEFAULT_SPEED)
        self.max_steering_angle = self._param('~max_steering_angle', teleop_keys.DEFAULT_MAX_STEERING_ANGLE)
        self.period = 1.0 / self._param('~rate', 1.0 / teleop_keys.DEFAULT_PERIOD, positive=True)
        self.pub = rospy.Publisher(TOPIC, msg_type, queue_size=10)
        self.published = 0

    def _param(self, name, default, positive=False):
        value = self.rospy.get_param(name, default)
        ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) \
            and (value > 0 if positive else value >= 0)
        if not ok:
            self.rospy.logwarn('keyboard_teleop: %s must be a finite number %s 0, got %r; using %g'
                               % (name, '>' if positive else '>=', value, default))
            return float(default)
        return float(value)

    def publish(self, command):
        msg = self.msg_type()
        msg.header.stamp = self.rospy.Time.now()
        msg.header.frame_id = 'base_link'
        msg.drive.speed = command.speed
        msg.drive.steering_angle = command.steering_angle
        self.pub.publish(msg)
        self.published += 1


def main(argv=None):
    if not os.environ.get('DISPLAY'):
        say('no display (DISPLAY is unset), so no keyboard window; drive with e.g. `rostopic pub -r 10 '
            '%s ackermann_msgs/AckermannDriveStamped "{drive: {speed: 0.5}}"`' % TOPIC)
        return
    try:
        import tkinter
    except ImportError as err:
        say('Python 3 tkinter is missing (%s): apt-get install python3-tk' % err)
        sys.exit(1)
    try:
        window = TkWindow(tkinter)
    except tkinter.TclError as err:
        say('cannot open display %s (%s), so no keyboard window; drive with rostopic pub on %s'
            % (os.environ.get('DISPLAY'), err, TOPIC))
        return

    import rospy
    from ackermann_msgs.msg import AckermannDriveStamped
    # Tk owns the main thread; signals are ours to handle (rospy's would not stop Tk's mainloop).
    rospy.init_node('keyboard_teleop', argv=argv, disable_signals=True)
    node = KeyboardTeleopNode(rospy, AckermannDriveStamped)
    keys = teleop_keys.KeyState(node.speed, node.max_steering_angle)
    controller = teleop_keys.TeleopController(keys, window, node.publish, period=node.period)
    window.bind(controller)
    window.keep_beside_the_3d_window()

    signals = []

    def on_signal(signum, _frame):
        signals.append(signal.Signals(signum).name)
        window.close(signals[-1])  # root.quit() only sets a flag: safe in a signal handler
    for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, on_signal)

    def report_callback_exception(exc, value, tb):
        rospy.logerr('keyboard_teleop: %s' % ''.join(traceback.format_exception(exc, value, tb)))
        window.close('exception in a Tk callback')
    window.root.report_callback_exception = report_callback_exception

    try:
        rospy.loginfo('keyboard_teleop: focus the "%s" window; W/S drive, A/D steer, Q quits '
                      '(speed %g m/s, steering %g rad)' % (WINDOW_TITLE, node.speed, node.max_steering_angle))
        window.run(lambda: signals[-1] if signals else ('ROS shutdown' if rospy.is_shutdown() else None))
        before = node.published
        controller.shutdown()
        if node.published > before:
            time.sleep(STOP_FLUSH_TIME)  # wall time: let the final stop leave before the connections close
    finally:
        window.destroy()
        rospy.loginfo('keyboard_teleop: exiting (%s)' % (window.close_reason or 'exception'))
        rospy.signal_shutdown(window.close_reason or 'exception')

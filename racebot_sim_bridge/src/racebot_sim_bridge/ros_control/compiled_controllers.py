"""Compiled ros_control controllers: a controller `type` racebot has no Python class for, made through pluginlib.

A package's C++ controller, built against racebot's controller_interface and hardware_interface
(upstream_compat) and exported with PLUGINLIB_EXPORT_CLASS and a plugin XML, loads by its `type` as in
ros_control: the controller_host module (src/cpp/controller_host.cpp) asks pluginlib for the class, initializes
it on the robot's joints (gazebo_ros_control's DefaultRobotHWSim: each joint's state, and the command interface
of its transmission) and drives it when the ControllerManager does, in its update order beside the Python
controllers. Its NodeHandles are roscpp's, which runs in the world server (started by `ensure_roscpp`).
"""
from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError


def _python_name(interface):
    """'hardware_interface::VelocityJointInterface' -> 'hardware_interface/VelocityJointInterface' (the Python
    controllers' spelling, which the manager's switch checks compare)."""
    return interface.replace('::', '/')


class CompiledController:
    """One C++ controller as the ControllerManager drives it (the methods of a Python controller)."""

    def __init__(self, host, ident, claimed):
        self._host, self._id = host, ident
        self._claimed = [(_python_name(iface), list(resources)) for iface, resources in claimed]
        self.update = lambda time, period: host.update(ident, time, period)  # one call, every control period

    def claimed_resources(self):
        return self._claimed

    def starting(self, time):
        self._host.starting(self._id, time)

    def stopping(self, time):
        self._host.stopping(self._id, time)

    def shutdown(self):
        if self._host is not None:
            self._host.unload(self._id)
            self._host = None


class CompiledControllers:
    """The C++ controllers pluginlib can make for one controller manager (namespace `ns`) on the joints of `hw`
    (a DefaultRobotHWSim). `ensure_roscpp()` starts roscpp in this process if it is not running; None where no
    master runs, and then no C++ controller loads (their NodeHandles need one)."""

    def __init__(self, ns, hw, ensure_roscpp=None, host=None):
        """host: the controller_host.Host to use, when it was made already (a compiled RobotHWSim's, whose
        handles the C++ controllers then get); else one is made over `hw`'s Python handles when first needed."""
        self.ns, self.hw, self.ensure_roscpp = ns, hw, ensure_roscpp
        self.host = host
        self.unavailable = None if ensure_roscpp is not None else 'no ROS master: C++ controllers need roscpp'

    def _ensure_host(self):
        if self.host is None and self.unavailable is None:
            try:
                from racebot_sim_bridge.ros_control import controller_host
            except ImportError as err:
                self.unavailable = ("racebot's controller host (controller_host) is not built (%s): run 'make build' "
                                    "in racebot's folder" % err)
                return None
            joints = [(n, self.hw.handles[n].interface, self.hw.handles[n]) for n in self.hw.names]
            self.host = controller_host.Host(self.ns, joints)
        return self.host

    def types(self):
        """Every controller type pluginlib knows (its packages' exported plugin XMLs), [] without a host."""
        host = self._ensure_host()
        return host.types() if host is not None else []

    def built(self, type_name):
        """Whether a package exports `type_name` to pluginlib and its library is there (built): then it runs, not
        racebot's Python controller of that type (which stays the fallback: racebot's own plugin XMLs name no
        library)."""
        host = self._ensure_host()
        return host is not None and host.built(type_name)

    def make(self, name, type_name):
        """The controller `name` of C++ type `type_name`, initialized; None when pluginlib has no such type;
        ControllerInitError saying why when it cannot be made or its init fails."""
        host = self._ensure_host()
        if host is None or not host.available(type_name):
            return None
        self.ensure_roscpp()  # its NodeHandles
        try:
            ident = host.load(name, type_name)
        except RuntimeError as err:
            raise ControllerInitError('C++ controller %s: %s' % (type_name, err)) from None
        return CompiledController(host, ident, host.claimed(ident))

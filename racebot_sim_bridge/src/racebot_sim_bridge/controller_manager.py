"""ros_control's controller manager for one simulated robot.

`ControllerManager` holds ros_control's semantics (load, unload, switch with strictness, list,
update) and knows no ROS; `ControllerManagerServices` serves it under
`<robotNamespace>/controller_manager/` with controller_manager_msgs, as ros_control does. The
simulator's node is not named `<ns>/controller_manager`: the tutorial's spawner takes that name.
Every refusal is logged as an error saying what was wrong and what to do, and answered ok=false.
"""
import collections
import threading

from .controllers import CONTROLLER_TYPES, ControllerInitError
from .hardware import cpp_name

BEST_EFFORT = 1
STRICT = 2

Entry = collections.namedtuple('Entry', 'controller type_name')


class ControllerManager(object):
    def __init__(self, ns, hw, get_params, io, log, types=None):
        """get_params(name) -> the dict under <ns>/<name>, or None; log has error/warn/info."""
        self.ns = '/' + ns.strip('/') if ns.strip('/') else ''
        self.hw = hw
        self.get_params = get_params
        self.io = io
        self.log = log
        self.types = dict(types or CONTROLLER_TYPES)
        self.loaded = collections.OrderedDict()  # name -> Entry, in load order (= update order)
        self.state = {}  # name -> 'initialized' | 'running' | 'stopped'
        self.lock = threading.RLock()

    # -- the services' semantics ------------------------------------------------------------------
    def load(self, name):
        with self.lock:
            if not name:
                self.log.error('Could not load a controller with an empty name; give the name of a '
                               'controller whose configuration is on the parameter server')
                return False
            if name in self.loaded:
                self.log.error("A controller named '%s' was already loaded inside the controller manager "
                               "(%s); unload it first, or give the new one another name" % (name, self.ns or '/'))
                return False
            params = self.get_params(name)
            where = '%s/%s' % (self.ns, name)
            if not isinstance(params, dict) or 'type' not in params:
                self.log.error("Could not load controller '%s' because the type was not specified. Did you load "
                               "the controller configuration on the parameter server (namespace: '%s')? e.g. "
                               "rosparam load your_controllers.yaml, with '%s: {type: ...}' under '%s'"
                               % (name, where, name, self.ns or '/'))
                return False
            type_name = params['type']
            cls = self.types.get(type_name) if isinstance(type_name, str) else None
            if cls is None:
                self.log.error("Could not load controller '%s' because controller type '%s' does not exist. "
                               "Use 'rosservice call %s/controller_manager/list_controller_types' to get the "
                               "available types" % (name, type_name, self.ns))
                return False
            try:
                controller = cls(name, self.ns, params, self.hw, self.io)
            except ControllerInitError as err:
                self.log.error("Initializing controller '%s' failed: %s" % (name, err))
                return False
            except Exception as err:  # a malformed configuration: ros_control catches init's exceptions too
                self.log.error("Initializing controller '%s' failed: its configuration under '%s' is malformed "
                               "(%s: %s)" % (name, where, type(err).__name__, err))
                return False
            self.loaded[name] = Entry(controller, type_name)
            self.state[name] = 'initialized'
            self.log.info("Loaded '%s' (%s)" % (name, type_name))
            return True

    def unload(self, name):
        with self.lock:
            if name not in self.loaded:
                self.log.error("Could not unload controller with name '%s' because no controller with this name "
                               "exists (loaded: %s)" % (name, ', '.join(self.loaded) or 'none'))
                return False
            if self.state[name] == 'running':
                self.log.error("Could not unload controller with name '%s' because it is still running; stop it "
                               "first with switch_controller" % name)
                return False
            self.loaded.pop(name).controller.shutdown()
            del self.state[name]
            self.log.info("Unloaded '%s'" % name)
            return True

    def switch(self, start, stop, strictness, time):
        with self.lock:
            if strictness not in (BEST_EFFORT, STRICT):
                self.log.warn('Controller Manager: To switch controllers you need to specify a strictness level of '
                              'controller_manager_msgs::SwitchController::STRICT (%d) or ::BEST_EFFORT (%d). '
                              'Defaulting to ::BEST_EFFORT.' % (STRICT, BEST_EFFORT))
                strictness = BEST_EFFORT
            start, stop = list(start), list(stop)
            for verb, names in (('stop', stop), ('start', start)):
                for n in list(names):
                    problem = None
                    if n not in self.loaded:
                        problem = ("Could not %s controller with name '%s' because no controller with this name "
                                   "exists (loaded: %s)" % (verb, n, ', '.join(self.loaded) or 'none'))
                    elif verb == 'stop' and self.state[n] != 'running' and n not in start:
                        problem = "Could not stop controller '%s' since it is not running" % n
                    elif verb == 'start' and self.state[n] == 'running' and n not in stop:
                        problem = "Could not start controller '%s' since it is already running" % n
                    if problem:
                        if strictness == STRICT:
                            self.log.error(problem + ' (STRICT switch refused; nothing was changed)')
                            return False
                        self.log.warn(problem + ' (BEST_EFFORT: skipped)')
                        names.remove(n)
            # Resource conflicts among the controllers that would run afterwards.
            after = [n for n in self.loaded if (self.state[n] == 'running' and n not in stop) or n in start]
            owners = {}
            for n in after:
                for iface, resources in self.loaded[n].controller.claimed_resources():
                    for r in resources:
                        owners.setdefault((iface, r), []).append(n)
            conflicts = {k: v for k, v in owners.items() if len(v) > 1}
            if conflicts:
                for (iface, r), who in sorted(conflicts.items()):
                    self.log.error('Resource conflict on [%s]. Controllers = [%s]; stop one of them in the same '
                                   'switch' % (r, ', '.join(who)))
                self.log.error('Could not switch controllers, due to resource conflict')
                return False
            for n in stop:
                if self.state[n] == 'running':
                    self.loaded[n].controller.stopping(time)
                    self._zero_claimed(n)
                    self.state[n] = 'stopped'
            for n in start:
                self.loaded[n].controller.starting(time)
                self.state[n] = 'running'
            return True

    def _zero_claimed(self, name):
        # A stopped controller's joints get no effort (ros_control leaves the last one in force,
        # which lets a stopped wheel controller keep accelerating the car).
        for iface, resources in self.loaded[name].controller.claimed_resources():
            for r in resources:
                h = self.hw.handles.get(r)
                if h is not None and iface == h.interface:
                    h.command = 0.0 if iface != 'hardware_interface/PositionJointInterface' else h.position

    def list(self):
        with self.lock:
            return [(n, e.type_name, self.state[n], e.controller.claimed_resources()) for n, e in self.loaded.items()]

    def reload_libraries(self, force_kill, time):
        with self.lock:
            if self.loaded and not force_kill:
                self.log.error('Controller manager: Cannot reload controller libraries because there are still %d '
                               'controllers loaded; unload them first, or call with force_kill: true'
                               % len(self.loaded))
                return False
            running = [n for n in self.loaded if self.state[n] == 'running']
            if running:
                self.switch([], running, BEST_EFFORT, time)
            for n in reversed(list(self.loaded)):
                self.unload(n)
            return True

    # -- the update loop ---------------------------------------------------------------------------
    def update(self, time, period, reset_controllers=False):
        """ros_control's update: restart running controllers on a reset, then update them in order."""
        with self.lock:
            if reset_controllers:
                for n, e in self.loaded.items():
                    if self.state[n] == 'running':
                        e.controller.stopping(time)
                        e.controller.starting(time)
            for n, e in self.loaded.items():
                if self.state[n] == 'running':
                    try:  # free when nothing is raised (Python 3.11)
                        e.controller.update(time, period)
                    except Exception as err:  # one broken controller must not stop the simulation
                        self._stop_failed(n, time, err)

    def _stop_failed(self, name, time, err):
        self.log.error("Controller '%s' raised %s in its update (%s); it is stopped and its joints get no "
                       "command. Fix its configuration, then unload, load and start it again."
                       % (name, type(err).__name__, err))
        try:
            self.loaded[name].controller.stopping(time)
        except Exception:  # noqa: BLE001 (already failing; stopping is best effort)
            pass
        self._zero_claimed(name)
        self.state[name] = 'stopped'

    def shutdown(self):
        with self.lock:
            for e in self.loaded.values():
                e.controller.shutdown()
            self.loaded.clear()
            self.state.clear()


class ControllerManagerServices(object):
    """The six controller_manager services of one ControllerManager, served with rospy."""

    def __init__(self, rospy, manager, now):
        """now() -> current simulated time in seconds (for starting/stopping)."""
        from controller_manager_msgs import srv
        from controller_manager_msgs.msg import ControllerState, HardwareInterfaceResources
        self.rospy = rospy
        self.manager = manager
        self.now = now
        self._state_cls, self._res_cls = ControllerState, HardwareInterfaceResources
        base = manager.ns + '/controller_manager/'
        self.services = [
            rospy.Service(base + 'load_controller', srv.LoadController,
                          lambda r: srv.LoadControllerResponse(manager.load(r.name))),
            rospy.Service(base + 'unload_controller', srv.UnloadController,
                          lambda r: srv.UnloadControllerResponse(manager.unload(r.name))),
            rospy.Service(base + 'switch_controller', srv.SwitchController,
                          lambda r: srv.SwitchControllerResponse(
                              manager.switch(r.start_controllers, r.stop_controllers, r.strictness, now()))),
            rospy.Service(base + 'list_controllers', srv.ListControllers, self._list),
            rospy.Service(base + 'list_controller_types', srv.ListControllerTypes,
                          lambda r: srv.ListControllerTypesResponse(
                              sorted(manager.types), ['controller_interface::ControllerBase'] * len(manager.types))),
            rospy.Service(base + 'reload_controller_libraries', srv.ReloadControllerLibraries,
                          lambda r: srv.ReloadControllerLibrariesResponse(
                              manager.reload_libraries(r.force_kill, now()))),
        ]

    def _list(self, _req):
        from controller_manager_msgs.srv import ListControllersResponse
        out = []
        for name, type_name, state, claimed in self.manager.list():
            out.append(self._state_cls(name=name, state=state, type=type_name, claimed_resources=[
                self._res_cls(hardware_interface=cpp_name(iface), resources=list(res)) for iface, res in claimed]))
        return ListControllersResponse(out)

    def shutdown(self):
        for s in self.services:
            s.shutdown()

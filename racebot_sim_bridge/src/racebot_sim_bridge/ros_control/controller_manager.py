"""ros_control's controller manager for one simulated robot.

`ControllerManager` holds ros_control's semantics (load, unload, switch with strictness, list,
update) and knows no ROS; `ControllerManagerServices` serves it under
`<robotNamespace>/controller_manager/` with controller_manager_msgs, as ros_control does. The
simulator's node is not named `<ns>/controller_manager`: the tutorial's spawner takes that name.
Every refusal is logged as an error saying what was wrong and what to do, and answered ok=false.

A switch is controller_manager 0.20's: checked when asked (request_switch, with controller_switch.py's
checks), carried out by the next update() in the simulation loop, its caller waiting for that
(wait_for_switch), so a switch_controller call while the world is paused waits for the unpause, or
gives up after its timeout + 1 s of wall time. The controller types are given to the manager (type
name -> class), as pluginlib's loader gives them upstream: it imports no controller.
"""
import collections
import threading
from time import monotonic

from racebot_sim_bridge.ros_control.controller_interface import ControllerInitError
from racebot_sim_bridge.ros_control.controller_switch import BEST_EFFORT, plan_switch
from racebot_sim_bridge.ros_control.hardware_interface import cpp_name
from racebot_sim_bridge.supported_table import WHERE

Entry = collections.namedtuple('Entry', 'controller type_name')


class ControllerManager:
    def __init__(self, ns, hw, get_params, io, log, types, compiled=None):
        """get_params(name) -> the dict under <ns>/<name>, or None; log has error/warn/info; types: controller
        type name -> class, what load() builds from (given by whoever builds the manager, as pluginlib's
        loader gives upstream's: gazebo_ros_control's plugin passes ros_controllers' CONTROLLER_TYPES);
        compiled: the C++ controllers pluginlib can make (compiled_controllers.CompiledControllers), asked for a
        type `types` lacks, or None."""
        self.ns = '/' + ns.strip('/') if ns.strip('/') else ''
        self.hw = hw
        self.get_params = get_params
        self.io = io
        self.log = log
        self.types = dict(types)
        self.compiled = compiled
        self.loaded = collections.OrderedDict()  # name -> Entry, in load order (= update order)
        self.state = {}  # name -> 'initialized' | 'running' | 'stopped'
        self.pending = None  # the accepted SwitchRequest the next update carries out
        self._loading = set()  # names being loaded (built outside the lock, not in `loaded` yet)
        self._closed = False  # shut down: a load that finishes now is undone
        self.lock = threading.RLock()
        self._running = []  # (name, controller) of the running ones in load order: what every update walks

    # -- the services' semantics ------------------------------------------------------------------
    def load(self, name):
        """load_controller. The slow part (the parameter read, the controller's publishers and
        subscribers: calls to the master) runs without `lock`, which every update needs, so the
        physics steps on while a controller loads; the lock is taken only to check and insert."""
        with self.lock:
            if not name:
                self.log.error('Could not load a controller with an empty name; give the name of a '
                               'controller whose configuration is on the parameter server')
                return False
            if name in self.loaded or name in self._loading:
                self.log.error("A controller named '%s' was already loaded inside the controller manager "
                               "(%s); unload it first, or give the new one another name" % (name, self.ns or '/'))
                return False
            self._loading.add(name)  # the name is taken while it loads: a second load of it is refused
        made = None
        try:
            made = self._make(name)
        finally:
            with self.lock:
                self._loading.discard(name)
                closed = self._closed
                if made is not None and not closed:
                    self.loaded[name] = made
                    self.state[name] = 'initialized'
        if made is None:
            return False
        if closed:  # shut down while it loaded (its model was deleted): undone
            made.controller.shutdown()
            self.log.error("Could not load controller '%s': its controller manager (%s) was shut down while it "
                           "loaded (the model was deleted); spawn the model again, then load it"
                           % (name, self.ns or '/'))
            return False
        self.log.info("Loaded '%s' (%s)" % (name, made.type_name))
        return True

    def _make(self, name):
        """The controller `name` built from its parameters (an Entry), or None with the error logged."""
        params = self.get_params(name)
        where = '%s/%s' % (self.ns, name)
        if not isinstance(params, dict) or 'type' not in params:
            self.log.error("Could not load controller '%s' because the type was not specified. Did you load "
                           "the controller configuration on the parameter server (namespace: '%s')? e.g. "
                           "rosparam load your_controllers.yaml, with '%s: {type: ...}' under '%s'"
                           % (name, where, name, self.ns or '/'))
            return None
        type_name = params['type']
        cls = self.types.get(type_name) if isinstance(type_name, str) else None
        # a C++ controller: of a type racebot has no class for, or whose library a package built (that runs, as
        # in ros_control; racebot's class of the same type is the fallback when it does not load)
        if isinstance(type_name, str) and self.compiled is not None and (cls is None or self.compiled.built(type_name)):
            try:
                made = self.compiled.make(name, type_name)
            except ControllerInitError as err:
                if cls is None:
                    self.log.error("Initializing controller '%s' failed: %s" % (name, err))
                    return None
                self.log.warn("Controller '%s': the built %s did not load (%s); racebot's Python %s runs instead"
                              % (name, type_name, err, type_name))
                made = None
            if made is not None:
                return Entry(made, type_name)
        if cls is None:
            self.log.error("Could not load controller '%s' because controller type '%s' does not exist. "
                           "Use 'rosservice call %s/controller_manager/list_controller_types' to get the "
                           "available types; %s says which ros_controllers racebot has and which not yet, and "
                           "how a package's own C++ controller is exported to pluginlib"
                           % (name, type_name, self.ns, WHERE))
            return None
        try:
            return Entry(cls(name, self.ns, params, self.hw, self.io), type_name)
        except ControllerInitError as err:
            self.log.error("Initializing controller '%s' failed: %s" % (name, err))
        except Exception as err:  # a malformed configuration: ros_control catches init's exceptions too
            self.log.error("Initializing controller '%s' failed: its configuration under '%s' is malformed "
                           "(%s: %s)" % (name, where, type(err).__name__, err))
        return None

    def unload(self, name):
        """unload_controller; the controller's topics are unregistered (calls to the master) after
        it has left the update loop, without `lock`."""
        with self.lock:
            if name not in self.loaded:
                self.log.error("Could not unload controller with name '%s' because no controller with this name "
                               "exists (loaded: %s)" % (name, ', '.join(self.loaded) or 'none'))
                return False
            if self.state[name] == 'running':
                self.log.error("Could not unload controller with name '%s' because it is still running; stop it "
                               "first with switch_controller" % name)
                return False
            entry = self.loaded.pop(name)
            del self.state[name]
            self._refresh_running()
        entry.controller.shutdown()
        self.log.info("Unloaded '%s'" % name)
        return True

    def request_switch(self, start, stop, strictness, start_asap=False, timeout=0.0):
        """switch_controller's checks (controller_switch.plan_switch); returns the accepted SwitchRequest,
        which the next update() carries out, or None when refused (nothing changes)."""
        with self.lock:
            if self.pending is not None:
                self.log.error('Could not switch controllers: the previous switch is still waiting for the '
                               'simulation to update (is it paused?); unpause it, or call again later')
                return None
            self.pending = plan_switch(self.loaded, self.state, start, stop, strictness, start_asap, timeout,
                                       self.log)
            return self.pending

    def wait_for_switch(self, request, keep_waiting=lambda: True, clock=monotonic, poll=0.01):
        """Waits, as switch_controller's caller waits, for the update loop to carry `request` out;
        True once it has. Bounded in wall time as controller_manager 0.20 bounds it: forever when
        the request's timeout is 0, else timeout + 1 s (so a negative timeout shortens it). On
        giving up, or when keep_waiting() turns false (ROS shutting down), the switch is withdrawn:
        it never happens, and the answer is False."""
        begin = clock()
        while not request.done.wait(poll):
            elapsed = clock() - begin
            if not keep_waiting() or not (elapsed < request.timeout + 1.0 or request.timeout == 0):
                with self.lock:
                    if request.done.is_set():
                        break
                    request.cancel()
                    if self.pending is request:
                        self.pending = None
                if keep_waiting():
                    self.log.error('Could not switch controllers: the simulation did not update within the '
                                   'timeout (%g s + 1 s of wall time); is it paused? The switch was withdrawn'
                                   % request.timeout)
                return False
        return request.ok

    def switch(self, start, stop, strictness, start_asap=False, timeout=0.0, keep_waiting=lambda: True):
        """switch_controller: checks, then waits until an update has carried the switch out."""
        request = self.request_switch(start, stop, strictness, start_asap, timeout)
        return request is not None and self.wait_for_switch(request, keep_waiting)

    def _carry_out(self, request, time):
        """The accepted switch, at an update (ros_control's manageSwitch; DefaultRobotHWSim's joints are
        always ready, so the switch completes within this update and `timeout` never aborts it)."""
        for n in request.stop:
            if n in self.loaded and self.state[n] == 'running':
                self.loaded[n].controller.stopping(time)
                self._zero_claimed(n)
                self.state[n] = 'stopped'
        for n in request.start:
            if n not in self.loaded:
                continue
            if request.start_asap and self.state[n] == 'running':
                continue  # start_asap starts what does not run yet; without it every name is (re)started
            self.loaded[n].controller.starting(time)
            self.state[n] = 'running'
        self._refresh_running()
        request.finish(True)
        self.pending = None

    def _refresh_running(self):
        """A new list (an update walking the old one is not disturbed) after any change of state."""
        self._running = [(n, e.controller) for n, e in self.loaded.items() if self.state[n] == 'running']

    def _zero_claimed(self, name):
        # A stopped controller's joints get no effort (ros_control leaves the last one in force,
        # which lets a stopped wheel controller keep accelerating the car).
        for iface, resources in self.loaded[name].controller.claimed_resources():
            for r in resources:
                h = self.hw.handles.get(r)
                if h is not None and iface == h.interface:
                    h.command = 0.0 if iface != 'hardware_interface/PositionJointInterface' else h.position

    def type_names(self):
        """list_controller_types: the Python types, then the C++ ones pluginlib declares that they do not shadow."""
        names = sorted(self.types)
        if self.compiled is not None:
            names += sorted(set(self.compiled.types()) - set(self.types))
        return names

    def list(self):
        with self.lock:
            return [(n, e.type_name, self.state[n], e.controller.claimed_resources()) for n, e in self.loaded.items()]

    def reload_libraries(self, force_kill, keep_waiting=lambda: True):
        """reload_controller_libraries: refused while controllers are loaded, unless force_kill: then
        all are stopped (one BEST_EFFORT switch, carried out by the next update) and unloaded."""
        with self.lock:
            names = list(self.loaded)
        if names and not force_kill:
            self.log.error('Controller manager: Cannot reload controller libraries because there are still %d '
                           'controllers running; unload them first, or call with force_kill: true' % len(names))
            return False
        if names:
            if not self.switch([], names, BEST_EFFORT, keep_waiting=keep_waiting):
                self.log.error('Controller manager: Cannot reload controller libraries because failed to stop '
                               'running controllers')
                return False
            for n in names:
                if not self.unload(n):
                    self.log.error("Controller manager: Cannot reload controller libraries because failed to "
                                   "unload controller '%s'" % n)
                    return False
        return True

    # -- the update loop ---------------------------------------------------------------------------
    def update(self, time, period, reset_controllers=False):
        """ros_control's update: restart running controllers when asked (reset_controllers: its
        e-stop release; gazebo_ros_control never asks on a world reset), update them in load order,
        then carry out an accepted switch."""
        with self.lock:
            if reset_controllers:
                for n, e in self.loaded.items():
                    if self.state[n] == 'running':
                        e.controller.stopping(time)
                        e.controller.starting(time)
            for n, controller in self._running:
                try:  # free when nothing is raised (Python 3.11)
                    controller.update(time, period)
                except Exception as err:  # one broken controller must not stop the simulation
                    self._stop_failed(n, time, err)
            if self.pending is not None:
                self._carry_out(self.pending, time)

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
        self._refresh_running()

    def shutdown(self):
        with self.lock:
            self._closed = True
            if self.pending is not None:  # its caller stops waiting: the model is gone
                self.pending.cancel()
                self.pending = None
            for e in self.loaded.values():
                e.controller.shutdown()
            self.loaded.clear()
            self.state.clear()
            self._running = []


class ControllerManagerServices:
    """The six controller_manager services of one ControllerManager, served with rospy. As in
    ros_control, one call is served at a time (its services lock): a switch_controller waiting for
    the simulation to update holds the others back."""

    def __init__(self, rospy, manager):
        from controller_manager_msgs import srv
        from controller_manager_msgs.msg import ControllerState, HardwareInterfaceResources
        self.rospy = rospy
        self.manager = manager
        self.lock = threading.Lock()
        self._state_cls, self._res_cls = ControllerState, HardwareInterfaceResources
        running = lambda: not rospy.is_shutdown()
        base = manager.ns + '/controller_manager/'

        def serve(name, cls, answer):
            def handle(req):
                with self.lock:
                    return answer(req)
            return rospy.Service(base + name, cls, handle)
        self.services = [
            serve('load_controller', srv.LoadController, lambda r: srv.LoadControllerResponse(manager.load(r.name))),
            serve('unload_controller', srv.UnloadController,
                  lambda r: srv.UnloadControllerResponse(manager.unload(r.name))),
            serve('switch_controller', srv.SwitchController,
                  lambda r: srv.SwitchControllerResponse(manager.switch(
                      r.start_controllers, r.stop_controllers, r.strictness, r.start_asap, r.timeout, running))),
            serve('list_controllers', srv.ListControllers, self._list),
            serve('list_controller_types', srv.ListControllerTypes, self._list_types),
            serve('reload_controller_libraries', srv.ReloadControllerLibraries,
                  lambda r: srv.ReloadControllerLibrariesResponse(manager.reload_libraries(r.force_kill, running))),
        ]

    def _list_types(self, _req):
        from controller_manager_msgs.srv import ListControllerTypesResponse
        names = self.manager.type_names()
        return ListControllerTypesResponse(names, ['controller_interface::ControllerBase'] * len(names))

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

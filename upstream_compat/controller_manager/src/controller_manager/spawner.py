"""The ``spawner`` node: loads and starts controllers, stops and unloads them on shutdown.

Command line and behaviour follow ros_control's Noetic spawner:

    spawner [--stopped] [--wait-for TOPIC] [--namespace NS] [--timeout T] [--no-timeout]
            [--shutdown-timeout T] controller [controller ...]

1. wait for ``controller_manager/{load,switch,unload}_controller`` (relative names, resolved in
   the node's namespace, so ``<node ns="/racebot" ...>`` talks to /racebot/controller_manager/...;
   ``--namespace NS`` puts NS/ in front). While /use_sim_time is true and no /clock has arrived
   (time 0), a timeout only means the simulator is still starting: the spawner says so and
   keeps waiting;
2. with ``--wait-for TOPIC``, wait until std_msgs/Bool ``True`` arrives on TOPIC;
3. load every controller (an argument naming an existing YAML file is loaded onto the parameter
   server and its top-level keys are the controllers); a refused load is an error: the spawner
   takes down what it loaded and exits with status 1;
4. unless ``--stopped``, start them all with one STRICT switch_controller call;
5. spin; on shutdown stop them (one switch) and unload them in reverse order.

Beyond ros_control: while spinning, the spawner watches the controller manager it loaded into
(the node serving load_controller). If that goes away or is replaced (the simulator stopped or
restarted), its controllers went with it: the spawner says so once, with what to do, and forgets
them, so that its own shutdown later does not stop and unload the same-named controllers a new
spawner loaded into the new controller manager. ros_control's spawner would not notice.

``parse_args`` is pure (no ROS import) so it can be tested without a master.
"""

import argparse
import os
import sys
import time

DEFAULT_TIMEOUT = 30.0
WATCH_PERIOD = 1.0  # wall seconds between checks that the controller manager is still the same
SERVICE_SUFFIXES = ('load_controller', 'switch_controller', 'unload_controller')


def _non_negative_float(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError('%r is not a number' % text)
    if value < 0.0 or value != value:
        raise argparse.ArgumentTypeError('%r must be a number >= 0' % text)
    return value


def build_parser():
    """The argument parser of the spawner (no ROS needed)."""
    parser = argparse.ArgumentParser(
        prog='spawner',
        description='Loads and starts ros_control controllers; stops and unloads them when '
                    'the node shuts down.')
    parser.add_argument('--stopped', action='store_true',
                        help='load the controllers but do not start them')
    parser.add_argument('--wait-for', metavar='topic', dest='wait_for',
                        help='load nothing until std_msgs/Bool "True" arrives on this topic')
    parser.add_argument('--namespace', metavar='ns',
                        help='namespace of the controller_manager services '
                             '(default: the node\'s namespace)')
    parser.add_argument('--timeout', metavar='T', type=_non_negative_float,
                        default=DEFAULT_TIMEOUT,
                        help='how long to wait for the controller_manager services at start-up '
                             '[s] (default: %(default)g; 0 waits forever)')
    parser.add_argument('--no-timeout', action='store_true', dest='no_timeout',
                        help='wait for the controller_manager services forever')
    parser.add_argument('--shutdown-timeout', metavar='T', type=float, default=None,
                        dest='shutdown_timeout',
                        help='deprecated and ignored (kept so old launch files still work)')
    parser.add_argument('controllers', metavar='controller', nargs='+',
                        help='controllers to load: names (configured under <ns>/<name>) or '
                             'YAML files whose top-level keys are controller names')
    return parser


def parse_args(args=None):
    """Parse the spawner's command line (``args`` without the program name and ROS remaps)."""
    return build_parser().parse_args(args=args)


def startup_timeout(options):
    """Seconds to wait for the services, or None for no limit."""
    if options.no_timeout or options.timeout == 0.0:
        return None
    return options.timeout


def service_names(namespace=None):
    """The (load, switch, unload) service names, relative unless ``namespace`` is absolute."""
    prefix = namespace or ''
    if prefix and not prefix.endswith('/'):
        prefix += '/'
    return tuple(prefix + 'controller_manager/' + suffix for suffix in SERVICE_SUFFIXES)


class Spawner:
    """One spawner run. ROS modules are imported here, not at module level."""

    def __init__(self, options):
        import rospy
        from controller_manager_msgs import srv
        self.rospy = rospy
        self.srv = srv
        self.options = options
        self.timeout = startup_timeout(options)
        self.load_name, self.switch_name, self.unload_name = service_names(options.namespace)
        self.loaded = []
        self.started = False
        self.exit_code = 0
        self.manager_uri = None  # the node serving load_controller when the controllers were loaded

    # -- waiting ---------------------------------------------------------------------------------
    def _sim_time_not_started(self):
        rospy = self.rospy
        try:
            use_sim_time = rospy.get_param('/use_sim_time', False)
        except Exception:  # master gone: nothing to explain
            return False
        return bool(use_sim_time) and rospy.get_time() == 0.0

    def wait_for_service(self, name):
        """Wait for one service; True when it is there, False on timeout or shutdown."""
        rospy = self.rospy
        resolved = rospy.resolve_name(name)
        rospy.loginfo('Controller Spawner: Waiting for service %s', resolved)
        told_about_clock = False
        while not rospy.is_shutdown():
            # The timeout counts from when the simulator's time started, not from a wait that began
            # before it: a /clock arriving near the end of one wait would leave the spawn of the robot
            # (which brings the services) only the rest of that wait.
            waited_before_clock = self._sim_time_not_started()
            try:
                rospy.wait_for_service(resolved, timeout=self.timeout)
                return True
            except rospy.ROSInterruptException:
                return False
            except rospy.ROSException:
                if waited_before_clock and not self._sim_time_not_started():
                    rospy.loginfo('Controller Spawner: the simulator\'s time started; waiting up to %g s '
                                  'more for %s', self.timeout, resolved)
                    continue
                if self._sim_time_not_started():
                    if not told_about_clock:
                        rospy.logwarn(
                            'Controller Spawner: %s is not there after %g s, but /use_sim_time is '
                            'true and no /clock message has arrived yet (time is 0): the simulator '
                            'is probably still starting. Waiting for /clock and for the service...',
                            resolved, self.timeout)
                        told_about_clock = True
                    continue
                self._explain_missing_service(resolved)
                return False
        return False

    def _explain_missing_service(self, resolved):
        rospy = self.rospy
        ns = rospy.get_namespace()
        elsewhere = []
        try:
            import rosgraph
            _, _, services = rosgraph.Master(rospy.get_name()).getSystemState()
            suffix = '/' + resolved.rsplit('/', 2)[-2] + '/' + resolved.rsplit('/', 1)[-1]
            elsewhere = sorted(s for s, _ in services if s.endswith(suffix) and s != resolved)
        except Exception:
            pass
        hint = ('Controller Spawner couldn\'t find the expected controller_manager ROS interface: '
                '%s did not appear within %g s. Check that the simulator is running (it serves the '
                'controller_manager services once the robot is spawned) and that this spawner\'s '
                'namespace (node namespace %s%s) matches the robotNamespace of the '
                'gazebo_ros_control plugin in the URDF: the services live under '
                '<robotNamespace>/controller_manager/.'
                % (resolved, self.timeout if self.timeout is not None else float('inf'), ns,
                   ', --namespace %s' % self.options.namespace if self.options.namespace else ''))
        if elsewhere:
            hint += ' A controller manager is serving %s: use that namespace.' % ', '.join(elsewhere)
        else:
            hint += ' No controller_manager services are advertised at all right now.'
        rospy.logerr(hint)

    def wait_for_topic(self, topic):
        """Block until std_msgs/Bool True arrives on ``topic``; False on shutdown."""
        from std_msgs.msg import Bool
        rospy = self.rospy
        state = {'heard': False, 'value': False}

        def callback(msg):
            state['heard'] = True
            state['value'] = bool(msg.data)
        sub = rospy.Subscriber(topic, Bool, callback)
        rospy.loginfo('Controller Spawner: Waiting for "True" on %s', rospy.resolve_name(topic))
        started = time.time()
        warned = False
        try:
            while not state['value']:
                if rospy.is_shutdown():
                    return False
                if (not warned and not state['heard'] and self.timeout is not None
                        and time.time() - started > self.timeout):
                    rospy.logwarn('Controller Spawner hasn\'t heard anything from its "wait for" '
                                  'topic (%s)', rospy.resolve_name(topic))
                    warned = True
                time.sleep(0.01)
        finally:
            sub.unregister()
        return True

    # -- controllers ----------------------------------------------------------------------------
    def expand_controllers(self, names):
        """Controller names; YAML file arguments are uploaded and replaced by their keys."""
        import yaml
        rospy = self.rospy
        controllers = []
        for name in names:
            if os.path.isfile(name):
                with open(name) as f:
                    content = yaml.safe_load(f) or {}
                if not isinstance(content, dict):
                    raise ValueError('%s does not hold a mapping of controller names' % name)
                for key, value in content.items():
                    rospy.set_param(key, value)
                    controllers.append(key)
            else:
                controllers.append(name)
        return controllers

    def switch(self, start, stop):
        proxy = self.rospy.ServiceProxy(self.switch_name, self.srv.SwitchController)
        request = self.srv.SwitchControllerRequest(
            start_controllers=list(start), stop_controllers=list(stop),
            strictness=self.srv.SwitchControllerRequest.STRICT, start_asap=False, timeout=0.0)
        return proxy(request).ok

    def shutdown(self):
        """on_shutdown hook: stop what we started, unload what we loaded (reverse order)."""
        rospy = self.rospy
        if not self.loaded:
            return
        rospy.loginfo('Shutting down spawner. Stopping and unloading controllers...')
        try:
            if self.started:
                rospy.loginfo('Stopping all controllers...')
                if not self.switch([], self.loaded):
                    rospy.logwarn('Controller Spawner: stopping %s failed', ', '.join(self.loaded))
            unload = rospy.ServiceProxy(self.unload_name, self.srv.UnloadController)
            rospy.loginfo('Unloading all loaded controllers...')
            for name in reversed(self.loaded):
                rospy.loginfo('Trying to unload %s', name)
                if unload(name).ok:
                    rospy.loginfo('Succeeded in unloading %s', name)
                else:
                    rospy.logwarn('Controller Spawner: the controller manager refused to unload %s',
                                  name)
        except Exception as exc:  # master or simulator already gone during a launch shutdown
            rospy.logwarn('Controller Spawner couldn\'t reach controller_manager to take down '
                          'controllers (%s); they are gone anyway if the simulator stopped.', exc)
        self.loaded = []

    def run(self):
        rospy = self.rospy
        options = self.options
        for name in (self.load_name, self.switch_name, self.unload_name):
            if not self.wait_for_service(name):
                return 0 if rospy.is_shutdown() else 1

        if options.wait_for and not self.wait_for_topic(options.wait_for):
            return 0

        rospy.on_shutdown(self.shutdown)
        try:
            controllers = self.expand_controllers(options.controllers)
        except (OSError, ValueError) as exc:
            rospy.logerr('Controller Spawner: cannot read controller file: %s', exc)
            return 1

        load = rospy.ServiceProxy(self.load_name, self.srv.LoadController)
        try:
            for name in controllers:
                if rospy.is_shutdown():
                    return 0
                rospy.loginfo('Loading controller: %s', name)
                if load(name).ok:
                    self.loaded.append(name)
                    continue
                rospy.logerr(
                    'Failed to load %s: the controller manager refused it (its log says why: '
                    'usually no %s parameter - is the controller YAML loaded into the same '
                    'namespace? - an unknown type, a duplicate name or a joint the robot does '
                    'not have). Taking down the controllers loaded so far.',
                    name, rospy.resolve_name(
                        (options.namespace.rstrip('/') + '/' if options.namespace else '')
                        + name + '/type'))
                self.exit_code = 1
                rospy.signal_shutdown('failed to load controller %s' % name)
                return 1
            rospy.loginfo('Controller Spawner: Loaded controllers: %s', ', '.join(self.loaded))

            if not options.stopped and self.loaded and not rospy.is_shutdown():
                if self.switch(self.loaded, []):
                    self.started = True
                    rospy.loginfo('Started controllers: %s', ', '.join(self.loaded))
                else:
                    rospy.logerr('Failed to start controllers: %s (the controller manager\'s log '
                                 'says why, e.g. two controllers claiming the same joint)',
                                 ', '.join(self.loaded))
        except (rospy.ServiceException, rospy.ROSException) as exc:
            if rospy.is_shutdown():
                return 0
            rospy.logerr('Controller Spawner: a controller_manager service call failed (%s). Did '
                         'the simulator stop?', exc)
            self.exit_code = 1
            rospy.signal_shutdown('controller_manager service call failed')
            return 1

        self.manager_uri = self._provider(self.load_name)
        self.watch()
        return self.exit_code

    def _provider(self, service):
        """The URI of the node serving ``service`` now, or None."""
        try:
            import rosgraph
            return rosgraph.Master(self.rospy.get_name()).lookupService(self.rospy.resolve_name(service))
        except Exception:  # not served (rosgraph.MasterError) or master gone
            return None

    def watch(self):
        """Spin until shutdown, checking that the controller manager is still the one loaded into."""
        rospy = self.rospy
        try:
            while not rospy.is_shutdown():
                time.sleep(WATCH_PERIOD)  # wall time, as rospy.spin sleeps (its wallsleep is internal)
                self._check_manager()
        except KeyboardInterrupt:  # as rospy.spin(): SIGINT shuts the node down, quietly
            rospy.signal_shutdown('keyboard interrupt')

    def _check_manager(self):
        """Warn once and forget the controllers if their controller manager is gone or replaced."""
        rospy = self.rospy
        if not self.loaded or self.manager_uri is None or rospy.is_shutdown():
            return
        uri = self._provider(self.load_name)
        if uri != self.manager_uri:
            rospy.logwarn(
                'Controller Spawner: the controller manager this spawner loaded %s into (%s) %s: the '
                'simulator stopped or restarted, and those controllers went with it. This spawner '
                'will not load them again; start a new spawner (or give this one respawn="true" and '
                'restart it) to load them into the new controller manager.',
                ', '.join(self.loaded), rospy.resolve_name(self.load_name),
                'is gone' if uri is None else 'was replaced by another')
            self.loaded = []
            self.started = False


def main(argv=None):
    """Run the spawner node; returns the process exit status."""
    import rospy
    if argv is None:
        argv = sys.argv
    options = parse_args(rospy.myargv(argv=argv)[1:])
    rospy.init_node('spawner', anonymous=True)
    if options.shutdown_timeout is not None:
        rospy.logwarn('Controller Spawner: --shutdown-timeout is deprecated and has no effect.')
    return Spawner(options).run()


def run():
    """Entry point of scripts/spawner."""
    sys.exit(main())

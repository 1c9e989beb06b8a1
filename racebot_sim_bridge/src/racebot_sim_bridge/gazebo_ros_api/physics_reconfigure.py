"""gazebo_ros's physics dynamic_reconfigure server (PhysicsConfig) in the gazebo node's namespace.

`<ns>/set_parameters`, `<ns>/parameter_descriptions` and `<ns>/parameter_updates`, as
gazebo_ros_api_plugin (noetic) offers them, so `rosrun dynamic_reconfigure dynparam get /gazebo` and
rqt_reconfigure show and change the world's physics. As upstream, the first configuration is read from
the world (get_physics_properties), and a reconfigure that changes anything sends the whole
configuration to set_physics_properties: one implementation of what a physics change does.

One difference, on purpose: upstream's server learns nothing of a set_physics_properties call, so
`dynparam get` then shows stale numbers and the next reconfigure, even of one parameter, puts the
stale ones back. Here a successful set_physics_properties is published on parameter_updates, and a
refused reconfigure publishes the world's unchanged numbers instead of the refused ones.
"""
import threading

# PhysicsConfig name -> (GetPhysicsProperties response / SetPhysicsProperties request path, type)
FIELDS = [
    ('time_step', ('time_step',), float),
    ('max_update_rate', ('max_update_rate',), float),
    ('gravity_x', ('gravity', 'x'), float),
    ('gravity_y', ('gravity', 'y'), float),
    ('gravity_z', ('gravity', 'z'), float),
    ('auto_disable_bodies', ('ode_config', 'auto_disable_bodies'), bool),
    ('sor_pgs_precon_iters', ('ode_config', 'sor_pgs_precon_iters'), int),
    ('sor_pgs_iters', ('ode_config', 'sor_pgs_iters'), int),
    ('sor_pgs_w', ('ode_config', 'sor_pgs_w'), float),
    ('sor_pgs_rms_error_tol', ('ode_config', 'sor_pgs_rms_error_tol'), float),
    ('contact_surface_layer', ('ode_config', 'contact_surface_layer'), float),
    ('contact_max_correcting_vel', ('ode_config', 'contact_max_correcting_vel'), float),
    ('cfm', ('ode_config', 'cfm'), float),
    ('erp', ('ode_config', 'erp'), float),
    ('max_contacts', ('ode_config', 'max_contacts'), int),
]


def config_of(properties):
    """The PhysicsConfig values (a dict) of a GetPhysicsProperties response."""
    values = {}
    for name, path, kind in FIELDS:
        value = properties
        for attr in path:
            value = getattr(value, attr)
        values[name] = kind(value)
    return values


def fill_request(config, request):
    """`request` (a SetPhysicsPropertiesRequest) with the values of `config`; returns it."""
    for name, path, kind in FIELDS:
        target = request
        for attr in path[:-1]:
            target = getattr(target, attr)
        setattr(target, path[-1], kind(config[name]))
    return request


def changed(config, world):
    """The names whose value in `config` differs from the world's."""
    return [name for name, _path, kind in FIELDS if kind(config[name]) != world[name]]


class PhysicsReconfigure:
    """The server, on `physics` (an object with get_physics_properties, set_physics_properties and a
    physics_listeners list: racebot_sim_bridge's GazeboProperties)."""

    def __init__(self, rospy, physics, ns):
        from dynamic_reconfigure.server import Server
        from gazebo_msgs import srv
        from racebot_sim_bridge.gazebo_ros_api import physics_config as PhysicsConfig
        self.rospy = rospy
        self.physics = physics
        self.srv = srv
        self._inside = threading.local()  # this thread is in our callback: a world change is ours
        self._initialized = False
        self.server = Server(PhysicsConfig, self._reconfigure, namespace=ns)
        physics.physics_listeners.append(self.world_changed)
        rospy.loginfo('Physics dynamic reconfigure ready.')

    def _world(self):
        return config_of(self.physics.get_physics_properties(self.srv.GetPhysicsPropertiesRequest()))

    def _reconfigure(self, config, _level):
        world = self._world()
        if not self._initialized or getattr(self._inside, 'adopting', False):
            self._initialized = True
            config.update(world)
            return config
        names = changed(config, world)
        if names:
            request = fill_request(config, self.srv.SetPhysicsPropertiesRequest())
            self._inside.applying = True
            try:
                res = self.physics.set_physics_properties(request)
            finally:
                self._inside.applying = False
            if res.success:
                self.rospy.loginfo('physics dynamics reconfigure update complete (%s)' % ', '.join(names))
            else:
                self.rospy.logerr('physics dynamic reconfigure of %s refused, the world keeps its physics: %s'
                                  % (', '.join(names), res.status_message))
            world = self._world()
        config.update(world)  # what the world now has: a refused value does not linger in the server
        return config

    def world_changed(self):
        """GazeboProperties.physics_listeners: set_physics_properties changed the world; publish it."""
        if getattr(self._inside, 'applying', False):
            return  # our own reconfigure: the server publishes what our callback returns
        self._inside.adopting = True
        try:
            self.server.update_configuration({})
        finally:
            self._inside.adopting = False

    def shutdown(self):
        self.server.set_service.shutdown()
        self.server.update_topic.unregister()
        self.server.descr_topic.unregister()

"""gazebo_ros's physics property services: get_physics_properties, set_physics_properties.

gravity, time_step and max_update_rate change for real (the Simulator's step size, the world server's pace, the
PhysicsWorld's gravity), and ode_config.sor_pgs_iters sets the solver's iterations; the other ODE numbers are kept
and returned by get_physics_properties, without effect. They start as the world file's <physics> gives them.
Listeners (physics_reconfigure's) hear of every change.
"""
import math

from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup


class PhysicsProperties(ServiceGroup):
    """get_physics_properties and set_physics_properties over a Simulator; ``physics_listeners``: called with no
    arguments after set_physics_properties changed the world."""

    SERVICES = {'get_physics_properties': 'GetPhysicsProperties', 'set_physics_properties': 'SetPhysicsProperties'}

    def __init__(self, rospy, sim):
        from gazebo_msgs import msg
        super().__init__(rospy, sim)
        # what the world file's <physics> says (sdf_model.ODE_SETTINGS), as Gazebo's ODEPhysics reports it
        self.ode_config = msg.ODEPhysics(auto_disable_bodies=False, sor_pgs_rms_error_tol=0.0, **sim.spec.physics.ode)
        self.physics_listeners = []  # called with no arguments after set_physics_properties changed the world

    def get_physics_properties(self, _req):
        res = self.srv.GetPhysicsPropertiesResponse()
        with self.sim.lock:
            res.time_step = self.sim.step_size
            res.pause = self.sim.paused
            res.max_update_rate = self.sim.real_time_update_rate
            res.gravity.x, res.gravity.y, res.gravity.z = self.sim.world.gravity
            res.ode_config = self.ode_config
        res.success, res.status_message = True, 'GetPhysicsProperties: got properties'
        return res

    def set_physics_properties(self, req):
        res = self.srv.SetPhysicsPropertiesResponse()
        g = (req.gravity.x, req.gravity.y, req.gravity.z)
        if not (math.isfinite(req.time_step) and req.time_step > 0):
            return self.fail(res, 'SetPhysicsProperties: time_step must be a positive number of seconds, got %r; '
                                  'start from what get_physics_properties gives' % req.time_step)
        if not (math.isfinite(req.max_update_rate) and req.max_update_rate >= 0):
            return self.fail(res, 'SetPhysicsProperties: max_update_rate must be >= 0 updates per second (0: as '
                                  'fast as possible), got %r' % req.max_update_rate)
        if not frames.finite(*g):
            return self.fail(res, 'SetPhysicsProperties: gravity must be finite, got (%r, %r, %r)' % g)
        o = req.ode_config
        if not frames.finite(o.sor_pgs_w, o.sor_pgs_rms_error_tol, o.contact_surface_layer,
                             o.contact_max_correcting_vel, o.cfm, o.erp):
            return self.fail(res, 'SetPhysicsProperties: ode_config values must be finite')
        with self.sim.lock:
            if req.time_step != self.sim.step_size:
                self.sim.set_step_size(req.time_step)
            self.sim.real_time_update_rate = req.max_update_rate  # the world server paces by it
            self.sim.world.set_gravity(g)
            if o.sor_pgs_iters > 0:
                self.sim.world.set_solver(numSolverIterations=int(o.sor_pgs_iters))
            self.ode_config = o
        for listener in self.physics_listeners:  # outside the lock: a listener reads the properties back
            listener()
        res.success, res.status_message = True, 'physics engine updated'
        return res

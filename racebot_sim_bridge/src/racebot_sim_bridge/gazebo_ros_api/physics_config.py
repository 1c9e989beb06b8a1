"""gazebo_ros's PhysicsConfig: the description dynamic_reconfigure's Python server reads.

Upstream generates this module from gazebo_ros/cfg/Physics.cfg (noetic) at build time. Here it is
made at import from a table, so that building racebot needs no cfg generator: the same 15 parameters with
upstream's names, types, levels, descriptions, defaults and limits, laid out as the generator lays out
its modules (config_description, min, max, defaults, level, type, all_level).
"""
from racebot_sim_bridge.gazebo_ros_api.reconfigure_config import config_type


# name, type, level, description, default, min, max (gazebo_ros's Physics.cfg, noetic)
_PARAMETERS = [
    ('time_step', 'double', 1, 'Simulation world time step size in seconds, smaller time steps producesslower, '
     'more stable simulation.', 0.001, 0.0, 10.0),
    ('max_update_rate', 'double', 1, 'Simulator max update rate, -1 unlimited, 1 restricts to real-time if '
     'possible.', 60.0, 0.0, 1000.0),
    ('gravity_x', 'double', 1, 'Simulated gravity in the x direction.', 0.0, -100.0, 100.0),
    ('gravity_y', 'double', 1, 'Simulated gravity in the y direction.', 0.0, -100.0, 100.0),
    ('gravity_z', 'double', 1, 'Simulated gravity in the z direction.', -9.8, -100.0, 100.0),
    ('auto_disable_bodies', 'bool', 1, "Auto disable of bodies in simulation if body it's not moving.",
     False, False, True),
    ('sor_pgs_precon_iters', 'int', 1, 'Number of preconditioning iterations for SOR PGS LCP as implemented in '
     'quickstep.', 0, 0, 10000),
    ('sor_pgs_iters', 'int', 1, 'Number of iterations for SOR PGS LCP as implemented in quickstep.', 20, 0, 10000),
    ('sor_pgs_w', 'double', 1, 'Relaxation parameter for SOR PGS LCP, usually set to 1.3, but reduce to stabilize '
     'simulation.', 1.3, 0.0, 5.0),
    ('sor_pgs_rms_error_tol', 'double', 1, 'The number of scans to skip between each measured scan', -1.0, -1.0,
     10000.0),
    ('cfm', 'double', 1, "Constraint Force Mixing per ODE's users manual.", 0.0, 0.0, 10.0),
    ('erp', 'double', 1, "Error Reduction Parameter per ODE's users manual.", 0.2, 0.0, 10.0),
    ('contact_surface_layer', 'double', 1, 'Margin for penetration for which restorative forces are not applied.',
     0.001, 0.0, 10.0),
    ('contact_max_correcting_vel', 'double', 1, 'Maximum contact penetration correction velocity.', 100.0, 0.0,
     10000000.0),
    ('max_contacts', 'int', 1, 'Maximum number of contacts between any 2 bodies.', 100, 0, 10000000),
]

# The module's attributes (config_description, min, max, defaults, level, type, all_level), as the generator
# writes them: made from the table by racebot_sim_bridge's one maker of config types.
globals().update(vars(config_type(_PARAMETERS, 'Physics.cfg')))

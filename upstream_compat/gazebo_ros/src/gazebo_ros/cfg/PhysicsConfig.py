"""gazebo_ros's PhysicsConfig: the description dynamic_reconfigure's Python server reads.

Upstream generates this module from gazebo_ros/cfg/Physics.cfg (noetic) at build time. Here it is
written by hand, so that building racebot needs no cfg generator: the same 15 parameters with
upstream's names, types, levels, descriptions, defaults and limits, laid out as the generator lays out
its modules (config_description, min, max, defaults, level, type, all_level).
"""
from dynamic_reconfigure.encoding import extract_params

inf = float('inf')

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

_CTYPES = {'double': 'double', 'int': 'int', 'bool': 'bool'}


def _parameter(name, type_, level, description, default, min_, max_):
    return {'name': name, 'type': type_, 'default': default, 'level': level, 'description': description,
            'min': min_, 'max': max_, 'srcline': 0, 'srcfile': 'Physics.cfg', 'edit_method': '',
            'ctype': _CTYPES[type_], 'cconsttype': 'const ' + _CTYPES[type_]}


config_description = {'name': 'Default', 'type': '', 'state': True, 'cstate': 'true', 'id': 0, 'parent': 0,
                      'parameters': [_parameter(*p) for p in _PARAMETERS], 'groups': [],
                      'srcline': 0, 'srcfile': 'Physics.cfg', 'class': 'DEFAULT', 'parentclass': '',
                      'parentname': 'Default', 'field': 'default', 'upper': 'DEFAULT', 'lower': 'groups'}

min = {}
max = {}
defaults = {}
level = {}
type = {}
all_level = 0

for param in extract_params(config_description):
    min[param['name']] = param['min']
    max[param['name']] = param['max']
    defaults[param['name']] = param['default']
    level[param['name']] = param['level']
    type[param['name']] = param['type']
    all_level = all_level | param['level']

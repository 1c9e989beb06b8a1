"""dynamic_reconfigure config types made at run time, as the .cfg generator would write them.

No rospy. dynamic_reconfigure's Python Server takes a "config type": the module its cfg generator writes
(config_description, defaults, min, max, level, type, all_level). Upstream packages generate theirs at build
time from a .cfg script; racebot writes the same descriptions from a parameter table (each parameter's name,
type, level, description, default, min and max, as the .cfg gives them), so building racebot needs no cfg
generator and the servers offer exactly upstream's parameters: gazebo_ros's PhysicsConfig, hector's
SensorModelConfig and GNSSConfig.
"""
from types import SimpleNamespace

_CTYPES = {'double': 'double', 'int': 'int', 'bool': 'bool', 'str': 'std::string'}


def _parameter(srcfile, name, type_, level, description, default, min_, max_):
    return {'name': name, 'type': type_, 'default': default, 'level': level, 'description': description,
            'min': min_, 'max': max_, 'srcline': 0, 'srcfile': srcfile, 'edit_method': '',
            'ctype': _CTYPES[type_], 'cconsttype': 'const ' + _CTYPES[type_]}


def config_type(parameters, srcfile):
    """The config type of `parameters`, [(name, type ('double', 'int', 'bool' or 'str'), level, description,
    default, min, max)] in the .cfg's order; srcfile: the .cfg's name (what rqt_reconfigure shows)."""
    from dynamic_reconfigure.encoding import extract_params
    description = {'name': 'Default', 'type': '', 'state': True, 'cstate': 'true', 'id': 0, 'parent': 0,
                   'parameters': [_parameter(srcfile, *p) for p in parameters], 'groups': [],
                   'srcline': 0, 'srcfile': srcfile, 'class': 'DEFAULT', 'parentclass': '',
                   'parentname': 'Default', 'field': 'default', 'upper': 'DEFAULT', 'lower': 'groups'}
    config = SimpleNamespace(config_description=description, min={}, max={}, defaults={}, level={}, type={},
                             all_level=0)
    for param in extract_params(description):
        name = param['name']
        config.min[name], config.max[name] = param['min'], param['max']
        config.defaults[name], config.level[name], config.type[name] = param['default'], param['level'], param['type']
        config.all_level |= param['level']
    return config

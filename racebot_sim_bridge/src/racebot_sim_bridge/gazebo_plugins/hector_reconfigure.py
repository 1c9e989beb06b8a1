"""The dynamic_reconfigure side of hector_gazebo_plugins' GPS and IMU: SensorModel.cfg and GNSS.cfg, and the
callbacks that read and write an error model or the GPS status through them (melodic-devel's
SensorModel_::dynamicReconfigureCallback and GazeboRosGps::dynamicReconfigureCallback).

The first call of a callback (dynamic_reconfigure's level ~0) fills the configuration from the model, as
hector's does; a change (level 1) sets the model from it. A 3-axis model shows the mean of its axes and
takes one value for all three, as hector's scalar_value and Vector3 assignment do.
"""
# name, type, level, description, default, min, max (hector_gazebo_plugins melodic-devel cfg/*.cfg)
SENSOR_MODEL_PARAMETERS = [
    ('gaussian_noise', 'double', 1, 'Standard deviation of the additive white Gaussian noise', 0.0, 0.0, 10.0),
    ('offset', 'double', 1, 'Zero-offset of the published sensor signal', 0.0, -10.0, 10.0),
    ('drift', 'double', 1, 'Standard deviation of the sensor drift', 0.0, 0.0, 10.0),
    ('drift_frequency', 'double', 1, 'Reciprocal of the time constant of the first-order drift model in Hz', 0.0,
     0.0, 1.0),
    ('scale_error', 'double', 1, 'Scale error', 1.0, 0.0, 2.0),
]
GNSS_PARAMETERS = [
    ('STATUS_FIX', 'bool', 1, 'unaugmented fix', True, False, True),
    ('STATUS_SBAS_FIX', 'bool', 1, 'fix with satellite-based augmentation', False, False, True),
    ('STATUS_GBAS_FIX', 'bool', 1, 'with ground-based augmentation', False, False, True),
    ('SERVICE_GPS', 'bool', 1, 'GPS service', True, False, True),
    ('SERVICE_GLONASS', 'bool', 1, 'GLONASS service', True, False, True),
    ('SERVICE_COMPASS', 'bool', 1, 'COMPASS service', True, False, True),
    ('SERVICE_GALILEO', 'bool', 1, 'GALILEO service', True, False, True),
]
# ErrorModel attribute of each SensorModel parameter
_MODEL_FIELDS = (('gaussian_noise', 'gaussian_noise'), ('offset', 'offset'), ('drift', 'drift'),
                 ('drift_frequency', 'drift_frequency'), ('scale_error', 'scale_error'))
# sensor_msgs/NavSatStatus bits
STATUS_NO_FIX, STATUS_SBAS_FIX, STATUS_GBAS_FIX = -1, 1, 2
SERVICES = (('SERVICE_GPS', 1), ('SERVICE_GLONASS', 2), ('SERVICE_COMPASS', 4), ('SERVICE_GALILEO', 8))

_types = {}


def config_types():
    """(SensorModelConfig, GNSSConfig), made once."""
    if not _types:
        from racebot_sim_bridge.gazebo_ros_api.reconfigure_config import config_type
        _types['sensor_model'] = config_type(SENSOR_MODEL_PARAMETERS, 'SensorModel.cfg')
        _types['gnss'] = config_type(GNSS_PARAMETERS, 'GNSS.cfg')
    return _types['sensor_model'], _types['gnss']


def sensor_model_callback(model, scalar=False):
    """The reconfigure callback of an ErrorModel; `scalar`: hector's one-axis SensorModel (the yaw's),
    whose value is axis 0."""
    def callback(config, level):
        if level == 1:
            for name, field in _MODEL_FIELDS:
                value = float(config[name])
                setattr(model, field, (value,) + tuple(getattr(model, field)[1:]) if scalar else (value,) * 3)
        else:
            for name, field in _MODEL_FIELDS:
                values = getattr(model, field)
                config[name] = values[0] if scalar else sum(values) / 3.0
        return config
    return callback


def gnss_callback(gps):
    """The reconfigure callback of the GPS status: `gps` has `status` and `service_bits`."""
    def callback(config, level):
        if level == 1:
            if not config['STATUS_FIX']:
                gps.status = STATUS_NO_FIX
            else:
                gps.status = ((STATUS_SBAS_FIX if config['STATUS_SBAS_FIX'] else 0)
                              | (STATUS_GBAS_FIX if config['STATUS_GBAS_FIX'] else 0))
            gps.service_bits = sum(bit for name, bit in SERVICES if config[name])
        else:
            config['STATUS_FIX'] = gps.status != STATUS_NO_FIX
            config['STATUS_SBAS_FIX'] = bool(gps.status & STATUS_SBAS_FIX)
            config['STATUS_GBAS_FIX'] = bool(gps.status & STATUS_GBAS_FIX)
            for name, bit in SERVICES:
                config[name] = bool(gps.service_bits & bit)
        return config
    return callback

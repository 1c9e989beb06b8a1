"""libgazebo_ros_wheel_slip.so (gazebo_plugins noetic-devel, on Gazebo 11's WheelSlipPlugin): per-wheel slip
compliance, changed at run time through dynamic_reconfigure.

Read as WheelSlipPlugin::Load: each `<wheel link_name="...">` with slip_compliance_lateral and
slip_compliance_longitudinal (0), wheel_normal_force (required > 0) and wheel_radius (else the radius of the link's
one cylinder or sphere collision); a wheel without link_name, naming no link, whose link has not exactly one
collision or one parent joint, or without a positive radius or normal force, is skipped with upstream's error; no
wheel left refuses the plugin ("No ODE links and surfaces found, plugin is disabled"). The ROS side
(GazeboRosWheelSlip): a dynamic_reconfigure server (gazebo_plugins' WheelSlip.cfg: slip_compliance_unitless_lateral
and slip_compliance_unitless_longitudinal, default -1, -1 to 20) under `<model>/<robotNamespace>/` (the spawn's
robot_namespace when the plugin has none; `wheel_slip/` when that is none, empty or '/'); a value >= 0 sets that
compliance of every wheel, with upstream's info line.

Not simulated: the slip itself. ODE turns each compliance into the contact's force-dependent slip (slip1, slip2 =
radius * |spin rate| / wheel_normal_force * compliance, every update), letting the contact slide at a speed
proportional to the friction force; Bullet's contacts have no such softening, so here the wheels grip as with
compliance 0 (rigid Coulomb friction up to mu) whatever the values, which the plugin keeps and reports. It says so
in one warning. Gazebo's transport topics (~/<model>/wheel_slip/<link> slip vectors, .../lateral_compliance) are
not offered.
"""
import xml.etree.ElementTree as ET

from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import after_spawn, resolve

# name, type, level, description, default, min, max (gazebo_plugins noetic-devel cfg/WheelSlip.cfg)
WHEEL_SLIP_PARAMETERS = [
    ('slip_compliance_unitless_lateral', 'double', 0,
     'Unitless slip compliance (slip / friction) in the lateral direction.', -1.0, -1.0, 20.0),
    ('slip_compliance_unitless_longitudinal', 'double', 0,
     'Unitless slip compliance (slip / friction) in the longitudinal direction.', -1.0, -1.0, 20.0),
]
_config_type = []


def wheel_slip_config():
    """gazebo_plugins' WheelSlipConfig, made once."""
    if not _config_type:
        from racebot_sim_bridge.gazebo_ros_api.reconfigure_config import config_type
        _config_type.append(config_type(WHEEL_SLIP_PARAMETERS, 'WheelSlip.cfg'))
    return _config_type[0]


class Wheel:
    def __init__(self, link, lateral, longitudinal, normal_force, radius):
        self.link, self.lateral, self.longitudinal = link, lateral, longitudinal
        self.normal_force, self.radius = normal_force, radius


def _number(elem, tag, default):
    text = elem.findtext(tag)
    try:
        return default if text is None else float(text)
    except ValueError:
        return default


class WheelSlip(ModelPlugin):
    libraries = ('libgazebo_ros_wheel_slip.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        elem = spec.element if spec.element is not None else ET.Element('plugin')
        if elem.find('wheel') is None:
            raise PluginError('No wheel tags specified, plugin is disabled')
        self.wheels = []
        for wheel in elem.findall('wheel'):
            try:
                self.wheels.append(self._wheel(wheel))
            except ValueError as err:
                self.ctx.rospy.logerr('%s: %s' % (self.label, err))
        if not self.wheels:
            raise PluginError('No ODE links and surfaces found, plugin is disabled')
        text = after_spawn(spec.params.get('robotNamespace'), robot.spawn_namespace)  # spawn's walk fills it in
        ns = '' if text is None else text + '/'
        if ns in ('', '/', '//'):
            ns = 'wheel_slip/'
        self.namespace = resolve(robot.name + '/' + ns, ctx.sim.node_namespace)
        self.reconfigure_server(self.namespace, wheel_slip_config(), self.on_reconfigure)
        self.warn('slip compliance is not simulated: PyBullet contacts have no force-dependent slip (ODE\'s slip1 '
                  'and slip2), so the wheels %s grip as with compliance 0 (friction up to mu) whatever the values; '
                  'the compliances are read, kept and set through dynamic_reconfigure under %s, and change nothing '
                  'in the physics' % (', '.join(w.link for w in self.wheels), self.namespace))

    def _wheel(self, elem):
        name = elem.get('link_name')
        if name is None:
            raise ValueError('wheel element missing link_name attribute')
        model, where = self.robot.model, "in model [%s]" % self.robot.name
        if name not in model.links:
            raise ValueError('Could not find link named [%s] %s' % (name, where))
        merged = [n for n in model.links if model.lumped_link(n) == name]  # Gazebo's link holds theirs too
        collisions = [c for n in merged for c in model.links[n].collisions]
        if len(collisions) != 1:
            raise ValueError('There should be 1 collision in link named [%s] %s, but %d were found'
                             % (name, where, len(collisions)))
        if model.parent_joint(name) is None:
            raise ValueError('There should be 1 parent joint for link named [%s] %s, but 0 were found' % (name, where))
        radius = _number(elem, 'wheel_radius', 0.0)
        if radius <= 0 and collisions[0].kind in ('cylinder', 'sphere'):
            radius = collisions[0].radius
        if radius <= 0:
            raise ValueError('Found wheel radius [%g], which is not positive in link named [%s] %s'
                             % (radius, name, where))
        normal_force = _number(elem, 'wheel_normal_force', 0.0)
        if normal_force <= 0:
            raise ValueError('Found wheel normal force [%g], which is not positive in link named [%s] %s'
                             % (normal_force, name, where))
        return Wheel(name, _number(elem, 'slip_compliance_lateral', 0.0),
                     _number(elem, 'slip_compliance_longitudinal', 0.0), normal_force, radius)

    def on_reconfigure(self, config, level):
        for key, field, word in (('slip_compliance_unitless_lateral', 'lateral', 'lateral'),
                                 ('slip_compliance_unitless_longitudinal', 'longitudinal', 'longitudinal')):
            value = config[key]
            if value >= 0:
                self.info('Reconfigure request for the gazebo ros wheel_slip: %s. New %s slip compliance: %.3e'
                          % (self.robot.name, word, value))
                for wheel in self.wheels:
                    setattr(wheel, field, value)
        return config


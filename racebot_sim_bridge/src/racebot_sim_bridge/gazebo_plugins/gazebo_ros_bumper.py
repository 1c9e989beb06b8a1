"""libgazebo_ros_bumper.so (gazebo_plugins noetic-devel): a contact sensor's gazebo_msgs/ContactsState. Gazebo's
collision names, contact groups and wrenches: ../sensors/contact.py; PyBullet's contact points: contact_points.py.

Parameters as its Load(): robotNamespace (text + '/'; none: the node's namespace), bumperTopicName
(bumper_states), frameName (world) resolved with the tf_prefix parameter of its namespace. The contact sensor must
name one of its link's collisions (<contact><collision>), else it is refused.

As Gazebo's ContactSensor, each update holds the contacts of every physics step since the previous update (at
most the last 100), read while somebody listens (Gazebo reads them from the plugin's Load on: the first message
after a subscriber came holds only the steps since then).
"""
import collections

from gazebo_msgs.msg import ContactsState

from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.config_types import SensorConfigError, join_topic, set_frame
from racebot_sim_bridge.sensors.contact import urdf_collision_shapes
from racebot_sim_bridge.sensors.contact_points import CONTACT_STEPS_KEPT, LinkContacts


class BumperSensor(Sensor, libraries=('libgazebo_ros_bumper.so',), sensor_types=('contact',),
                   kind=SensorKind.BUMPER, main_topic='bumper'):
    """gazebo_ros_bumper: the contacts of the sensor's <contact><collision>s as gazebo_msgs/ContactsState, every
    sensor update: a state per pair of collisions and step since the last update (none when nothing touches)."""

    @classmethod
    def load(cls, config, sdf):
        spec = sdf.spec
        if not spec.contact_collisions or not all(spec.contact_collisions):
            raise SensorConfigError("%s: the contact sensor needs <contact><collision>NAME</collision></contact> "
                                    "naming one of its link's collisions" % sdf.what)
        ns = sdf.namespace(cls.kind)
        set_frame(config, sdf.params, 'world', ns)
        config.topics['bumper'] = join_topic(ns, sdf.params.get('bumperTopicName') or 'bumper_states')
        config.params['collisions'] = list(spec.contact_collisions)
        return config

    def __init__(self, manager, robot, spec, config):
        super().__init__(manager, robot, spec, config)
        self.link = self.mount.link
        self.shapes = urdf_collision_shapes(robot.model, self.link)
        known = [shape.name for shape in self.shapes]
        self.wanted = set(config.params['collisions'])  # as sdformat left them (description/sdf_reduction)
        written = {r.now: r.written for r in spec.rewrites if r.element == 'contact/collision'}
        for name in config.params['collisions']:
            if name not in known:  # Gazebo's bumper would report nothing, silently: say why once
                config.warnings.append(
                    "sensor '%s': <contact><collision> %r%s names no collision of link %r, so the bumper reports "
                    'no contact, as in Gazebo; Gazebo names its collisions %s'
                    % (spec.name, written.get(name, name),
                       ' (which sdformat rewrites to %r, its link being lumped)' % name if name in written else '',
                       self.link, ', '.join(repr(k) for k in known) or '(it has none)'))
        self.contacts = LinkContacts(self.sim.world, robot.body.id, self.mount.index, self.shapes, robot.name,
                                     self.link, self.wanted)
        # every step's contacts since the last update, as Gazebo's ContactSensor keeps them (at most 100 steps),
        # read while somebody listens
        self.steps = collections.deque(maxlen=CONTACT_STEPS_KEPT)
        self._last_step = self.sim.time
        self.advertise('bumper', ContactsState, 1)

    def wake_time(self):
        if self.listened():
            return self._last_step + self.sim.step_size
        return self.schedule.next

    def step(self, time):
        self._last_step = time
        if self.listened():
            self.steps.append(self.contacts.read())
        else:
            self.steps.clear()
        super().step(time)

    def update(self, time, stamp):
        if not self.listened():
            return
        groups = [group for step in self.steps for group in step]
        self.steps.clear()
        self.publishers['bumper'].publish(msgs.contacts_state(stamp, self.config.frame_id, groups, stamp.to_sec()))
        self.meter.tick()

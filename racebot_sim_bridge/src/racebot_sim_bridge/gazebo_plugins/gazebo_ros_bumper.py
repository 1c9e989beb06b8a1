"""libgazebo_ros_bumper.so (gazebo_plugins noetic-devel): a contact sensor's gazebo_msgs/ContactsState. Gazebo's
collision names, contact groups and wrenches: ../sensors/contact.py; PyBullet's contact points: contact_points.py.

Parameters as its Load(): robotNamespace (text + '/'; none: the node's namespace), bumperTopicName
(bumper_states), frameName (world) resolved with the tf_prefix parameter of its namespace. The contact sensor must
name one of its link's collisions (<contact><collision>), else it is refused.
"""
from gazebo_msgs.msg import ContactsState

from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.config_types import SensorConfigError, join_topic, set_frame
from racebot_sim_bridge.sensors.contact import group_contacts, urdf_collision_shapes
from racebot_sim_bridge.sensors.contact_points import CollisionKinds, CollisionNames, link_com, read_contacts


class BumperSensor(Sensor, libraries=('libgazebo_ros_bumper.so',), sensor_types=('contact',),
                   kind=SensorKind.BUMPER, main_topic='bumper'):
    """gazebo_ros_bumper: the contacts of the sensor's <contact><collision>s as
    gazebo_msgs/ContactsState, every sensor update (an empty list when nothing touches)."""

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
        self.body_id = robot.body.id
        self.model_name = robot.name
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
        self.names = CollisionNames(self.sim.world)
        self.kinds = CollisionKinds(self.sim.world.client)
        self.bodies_seen = None
        self.advertise('bumper', ContactsState, 1)

    def update(self, time, stamp):
        if not self.listened():
            return
        world = self.sim.world
        bodies = tuple(id(b) for b in world.bodies.values())
        if bodies != self.bodies_seen:  # a body came or went: PyBullet ids may have been reused
            self.names.forget()
            self.kinds.forget()
            self.bodies_seen = bodies
        index = self.mount.index
        points = read_contacts(world, self.names, self.body_id, index, self.shapes, self.model_name, self.link,
                               self.wanted, self.kinds)
        com, orientation = link_com(world.client, self.body_id, index)
        groups = group_contacts(points, com, orientation)
        self.publishers['bumper'].publish(msgs.contacts_state(stamp, self.config.frame_id, groups, stamp.to_sec()))
        self.meter.tick()

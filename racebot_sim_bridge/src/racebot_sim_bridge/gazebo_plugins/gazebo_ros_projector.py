"""libgazebo_ros_projector.so (gazebo_plugins noetic-devel): ROS topics that switch a Gazebo <projector> on and
off and change its texture.

Upstream (a model plugin) reads projector (the projector as `link/name`, published to on Gazebo's
`~/<model>/<projector>` topic), robotNamespace (text + '/', none: ''), projectorTopicName and textureTopicName
(both ''), subscribes (queue 1) to std_msgs/Int32 on projectorTopicName (enabled = data != 0) and std_msgs/String
on textureTopicName (a texture file name), and turns each message into a Gazebo msgs::Projector for the projector,
which the rendering engine draws as a frustum-projected texture. An empty topic name is roscpp's name of the
namespace itself.
racebot subscribes the same and keeps the state the messages set (`enabled`: None until the first Int32, then a
bool; `texture`: None until the first String), logging each change; a `projector` naming no <projector> of the
model is warned about. NOT rendered: racebot draws no projectors at all (the <projector> element is read only to
be moved when its link is lumped), so the texture is projected onto nothing, on or off, in PyBullet's window and in
camera images alike.
"""
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in


class Projector(ModelPlugin):
    libraries = ('libgazebo_ros_projector.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.projector = p.string('projector', '')
        projectors = ['%s/%s' % (e.reference, e.element.get('name')) for e in robot.model.gazebo_elements
                      if e.element.tag == 'projector']
        if self.projector not in projectors:
            self.warn("<projector>%s</projector> names no <projector> of the model (it has %s): Gazebo's messages "
                      'would reach none' % (self.projector, ', '.join(projectors) or 'none'))
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        self.enabled = None
        self.texture = None
        from std_msgs.msg import Int32, String
        self.topics = {}
        for role, tag, cls, callback in (('projector', 'projectorTopicName', Int32, self.on_switch),
                                         ('texture', 'textureTopicName', String, self.on_texture)):
            name = p.string(tag, '')
            topic = name_in(ns, name) if name else ns  # roscpp resolves '' to the namespace itself
            if topic == '/':
                self.warn('<%s> is empty and the namespace is the root: no topic (roscpp refuses "/")' % tag)
                continue
            self.topics[role] = topic
            self.subscriber(topic, cls, callback)
        self.info('projector %s: %s; racebot renders no projectors, so nothing is projected'
                  % (self.projector, ', '.join('%s on %s' % item for item in sorted(self.topics.items()))))

    def on_switch(self, msg):
        self.enabled = bool(msg.data)
        self.info('projector %s %s (not rendered)' % (self.projector, 'on' if self.enabled else 'off'))

    def on_texture(self, msg):
        self.texture = msg.data
        self.info('projector %s texture %s (not rendered)' % (self.projector, self.texture))

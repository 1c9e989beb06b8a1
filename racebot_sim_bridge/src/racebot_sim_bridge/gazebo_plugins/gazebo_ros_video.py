"""libgazebo_ros_video.so (gazebo_plugins noetic-devel): a visual plugin that shows a sensor_msgs/Image topic on a
textured square.

Upstream (GZ_REGISTER_VISUAL_PLUGIN, in a <visual>: `<gazebo reference="link"><visual><plugin ...>` in a URDF)
reads robotNamespace (''), topicName (image_raw), height (240) and width (320), warning about each one missing;
adds to the visual a 1 x 1 m square at z 0.51 in the visual's frame (the +z face of a unit box) textured
width x height BGRA; subscribes to topicName in robotNamespace (queue 1) and, before each render, draws the
latest image on it (cv_bridge to bgra8, resized to width x height). It runs in whichever of gzserver and gzclient
renders the scene.
racebot subscribes the same: the topic, the namespace (spawn's -robot_namespace fills an absent one), the queue;
it keeps the latest image and counts them (`frames`, `latest`). NOT shown: racebot's only view is PyBullet's
window, which draws the link's own visual as described: no square is added and no image is drawn on anything, so
the video is seen nowhere, and an image cv_bridge could not turn into bgra8 is not refused (upstream's callback
throws on it).
"""
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in

DEFAULTS = (('robotNamespace', '""'), ('topicName', 'image_raw'), ('height', '240'), ('width', '320'))


class Video(ModelPlugin):
    libraries = ('libgazebo_ros_video.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        missing = ['<%s> (%s)' % (tag, default) for tag, default in DEFAULTS if not p.has(tag)]
        if missing:  # upstream warns about each one
            self.warn('missing %s: using the defaults' % ', '.join(missing))
        self.height = p.integer('height', 240)
        self.width = p.integer('width', 320)
        ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        self.topic = name_in(ns, p.string('topicName', 'image_raw'))
        self.frames = 0
        self.latest = None
        from sensor_msgs.msg import Image
        self.subscriber(self.topic, Image, self.on_image)
        self.info('subscribed to %s (%d x %d); racebot shows no video: its window draws the visual as described'
                  % (self.topic, self.width, self.height))

    def on_image(self, msg):
        self.latest = msg  # one assignment: whoever reads it gets a whole message
        self.frames += 1

"""gazebo_ros_video (a visual plugin, read from <gazebo reference><visual>) and gazebo_ros_projector on a real
Simulator: the topics upstream subscribes to, in its namespaces, and the state their messages set. Neither draws
anything in racebot (SUPPORTED.md says what is not shown)."""
from sensor_msgs.msg import Image
from std_msgs.msg import Int32, String

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_projector import Projector
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_video import Video

from model_plugin_sim import PluginWorld

VIDEO = """<gazebo reference="box"><visual><plugin name="tv" filename="libgazebo_ros_video.so">
 <topicName>video</topicName><height>120</height><width>160</width></plugin></visual></gazebo>"""
PROJECTOR = """<gazebo reference="box"><projector name="texture_projector"><pose>0 0 0.2 0 0 0</pose>
 <texture>stereo_projection_pattern_alpha.png</texture><fov>0.959931088</fov><near_clip>0.1</near_clip>
 <far_clip>10</far_clip></projector></gazebo>
<gazebo><plugin name="projector_controller" filename="libgazebo_ros_projector.so">
 <projector>%s</projector><robotNamespace>lamp</robotNamespace><projectorTopicName>projector</projectorTopicName>
 <textureTopicName>texture</textureTopicName></plugin></gazebo>"""


def box(*blocks):
    return """<robot name="box">
 <link name="box"><inertial><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual></link>
 %s
</robot>""" % '\n'.join(blocks)


def plugin(w, cls):
    return next(p for p in w.manager.plugins['box'] if isinstance(p, cls))


def test_a_video_visual_plugin_subscribes_as_upstream(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        w.spawn('box', box(VIDEO), '/screen', (0.0, 0.0, 0.1))
        video = plugin(w, Video)
        assert (video.topic, video.width, video.height) == ('/screen/video', 160, 120)
        assert video.frames == 0 and video.latest is None
        assert [m for m in w.warnings() if 'missing <robotNamespace> ("")' in m]  # upstream warns the same
        image = Image(width=2, height=1, encoding='rgb8', step=6, data=bytes(6))
        w.fake.subscribers['/screen/video'](image)
        w.fake.subscribers['/screen/video'](image)
        w.run(0.01)
        assert video.frames == 2 and video.latest is image
        assert not w.errors() and not w.warnings('not simulated')
    finally:
        w.close()


def test_a_projector_is_switched_and_given_a_texture_by_its_topics(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        w.spawn('box', box(PROJECTOR % 'box/texture_projector'), '/', (0.0, 0.0, 0.1))
        projector = plugin(w, Projector)
        assert projector.topics == {'projector': '/lamp/projector', 'texture': '/lamp/texture'}  # robotNamespace/
        assert (projector.enabled, projector.texture) == (None, None)
        w.fake.subscribers['/lamp/projector'](Int32(1))
        assert projector.enabled is True
        w.fake.subscribers['/lamp/projector'](Int32(0))
        w.fake.subscribers['/lamp/texture'](String('checker.png'))
        assert (projector.enabled, projector.texture) == (False, 'checker.png')
        assert not w.warnings() and not w.errors()
    finally:
        w.close()


def test_a_projector_naming_none_of_the_models_is_warned_about(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        w.spawn('box', box(PROJECTOR % 'box/other'), '/', (0.0, 0.0, 0.1))
        assert w.warnings("<projector>box/other</projector> names no <projector> of the model (it has "
                          "box/texture_projector)")
        assert '/lamp/projector' in w.fake.subscribers  # the topics work all the same
    finally:
        w.close()

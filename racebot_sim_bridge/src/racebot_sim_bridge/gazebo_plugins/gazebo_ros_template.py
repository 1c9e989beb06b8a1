"""libgazebo_ros_template.so (gazebo_plugins noetic-devel): upstream's skeleton of a model plugin, which
reads no parameter and does nothing. Registered so that a robot naming it is not warned about."""
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin


class Template(ModelPlugin):
    libraries = ('libgazebo_ros_template.so',)

"""gazebo_ros's property services: models, joints, links, physics and lights.

get_model_properties, get_joint_properties, get_link_properties, set_link_properties,
set_joint_properties, get_physics_properties, set_physics_properties, get_light_properties,
set_light_properties, delete_light, with gazebo_ros_api_plugin's (noetic) fields, name lookups and
status messages, one module per kind: model_properties.py, joint_properties.py, link_properties.py (and
gravity_mode false as a force before each step), physics_properties.py, light_properties.py. Where PyBullet
cannot do what ODE does, the request fails and says why instead of pretending (each module says where).
"""
from racebot_sim_bridge.gazebo_ros_api.joint_properties import JointProperties
from racebot_sim_bridge.gazebo_ros_api.light_properties import LightProperties
from racebot_sim_bridge.gazebo_ros_api.link_properties import LinkProperties
from racebot_sim_bridge.gazebo_ros_api.model_properties import ModelProperties
from racebot_sim_bridge.gazebo_ros_api.physics_properties import PhysicsProperties
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroups


class GazeboProperties(ServiceGroups):
    """The property services of a Simulator, each handler reachable by its service's name. ``links`` holds the step
    hook that cancels gravity where it is off; ``physics_listeners`` (physics_reconfigure's) are called after
    set_physics_properties changed the world."""

    def __init__(self, rospy, sim):
        self.links = LinkProperties(rospy, sim)
        self.physics = PhysicsProperties(rospy, sim)
        self.physics_listeners = self.physics.physics_listeners
        super().__init__((ModelProperties(rospy, sim), JointProperties(rospy, sim), self.links, self.physics,
                          LightProperties(rospy, sim)))

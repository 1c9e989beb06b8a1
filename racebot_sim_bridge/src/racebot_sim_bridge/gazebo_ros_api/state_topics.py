"""gazebo_ros's state topics: <ns>/model_states and <ns>/link_states, published while somebody listens.

Each model's pose and twist (its model frame, as get_model_state gives it) and each link's, named scoped
`model::link` (a nested model's links are links of its outer model: outer::inner::link). The world server
publishes them after the world updates it is asked to (world_server.py), and only when somebody listens.
"""
from gazebo_msgs.msg import LinkStates, ModelStates

from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities
from racebot_sim_bridge.gazebo_ros_api.state_services import pose_msg, twist_msg


class StateTopics:
    """The two publishers of a Simulator's model and link states under `ns`."""

    def __init__(self, rospy, sim, ns):
        self.sim = sim
        self.entities = WorldEntities(sim.world)
        self.model_states_pub = rospy.Publisher(ns + '/model_states', ModelStates, queue_size=1)
        self.link_states_pub = rospy.Publisher(ns + '/link_states', LinkStates, queue_size=1)

    def states_wanted(self):
        """Whether somebody listens to model_states or link_states."""
        return self.model_states_pub.get_num_connections() > 0 or self.link_states_pub.get_num_connections() > 0

    def publish_states(self):
        """model_states and link_states, each only when somebody listens."""
        want_models = self.model_states_pub.get_num_connections() > 0
        want_links = self.link_states_pub.get_num_connections() > 0
        if not (want_models or want_links):
            return
        models, links = self.states(want_models, want_links)
        if want_models:
            self.model_states_pub.publish(models)
        if want_links:
            self.link_states_pub.publish(links)

    def states(self, want_models=True, want_links=True):
        """(ModelStates, LinkStates) of the world now, each left empty unless wanted. A nested model's links are
        links of its outer model: outer::inner::link."""
        with self.sim.lock:
            models, links = ModelStates(), LinkStates()
            for name, body in self.sim.world.bodies.items():
                if want_models:
                    pose, twist = self.entities.model_state(body)
                    models.name.append(name)
                    models.pose.append(pose_msg(pose))
                    models.twist.append(twist_msg(twist))
                if want_links:
                    for link in self.entities.link_names(body):
                        pose, twist = self.entities.link_state(body, link)
                        links.name.append('%s::%s' % (name, link))
                        links.pose.append(pose_msg(pose))
                        links.twist.append(twist_msg(twist))
        return models, links

"""What every group of gazebo_ros's /gazebo services shares: the Simulator, the world's entities, the handlers by
service name, and a refusal as gazebo_ros_api_plugin words it.

GazeboServices (services.py) advertises the handlers of every group in gazebo_ros's order: SpawnServices,
StateServices, WorldControl, GazeboProperties' groups (models, joints, links, physics, lights) and GazeboForces.
"""
from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities


def refused(res, status):
    """`res` answering the call with success false and `status` (upstream's words)."""
    res.success, res.status_message = False, status
    return res


class ServiceGroup:
    """A group of /gazebo services over a Simulator, each answered by the method named as the service.

    SERVICES: {service name: the name of its gazebo_msgs/srv type, or the type itself}, which ``handlers`` turns
    into {service name: (type, handler)} for GazeboServices to advertise."""

    SERVICES = {}

    def __init__(self, rospy, sim):
        from gazebo_msgs import srv
        self.rospy = rospy
        self.sim = sim
        self.srv = srv
        self.entities = WorldEntities(sim.world)

    @property
    def handlers(self):
        return {name: (getattr(self.srv, kind) if isinstance(kind, str) else kind, getattr(self, name))
                for name, kind in self.SERVICES.items()}

    def logged(self, message):
        """`message`, logged as an error: for a response whose status says it too."""
        self.rospy.logerr(message)
        return message

    def fail(self, res, status, log=None):
        """refused(res, status), with `log` (else the status itself) logged as an error."""
        self.rospy.logerr(status if log is None else log)
        return refused(res, status)


class ServiceGroups:
    """Several ServiceGroups answering as one: their handlers merged in ``handlers``, each handler reachable as an
    attribute named as its service (``api.get_model_state(req)`` answers as the service does)."""

    def __init__(self, groups):
        self.handlers = {name: handler for group in groups for name, handler in group.handlers.items()}

    def __getattr__(self, name):
        handlers = self.__dict__.get('handlers', {})
        if name in handlers:
            return handlers[name][1]
        raise AttributeError("%s has no attribute or service '%s'" % (type(self).__name__, name))

"""gazebo_ros's PhysicsConfig (upstream generates it from cfg/Physics.cfg), for clients that import it from
gazebo_ros as they would upstream. The description lives with the server that uses it, in racebot_sim_bridge,
so that the simulator keeps its physics reconfigure server where a real gazebo_ros replaces this one."""
from racebot_sim_bridge.gazebo_ros_api.physics_config import *  # noqa: F401,F403

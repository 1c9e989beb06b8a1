"""The bench's ROS node and what it reads of a running world server: its pid, its /gazebo services, the
real-time factor and CPU share over a window, the racebot's controllers coming up. Shared by the scenarios
(scenarios.py) and the fleet part (fleet.py); rospy is imported only when called."""
import time
import xmlrpc.client

from . import common
from .common import BenchError

WORLD_SERVER = '/gazebo'
LIST_CONTROLLERS = common.NAMESPACE + '/controller_manager/list_controllers'


def init_node(name, sim_time=False):
    """rospy.init_node. With sim_time False the node keeps wall time and never subscribes to /clock:
    rospy reads /use_sim_time once, in init_node, so the node must start before the launch sets it
    (rospy has no public way to opt out afterwards)."""
    import rospy
    if not sim_time and rospy.get_param('/use_sim_time', False):
        raise BenchError('/use_sim_time is already set: start the bench node (%s) before the launch, or it '
                         'subscribes to /clock and costs the simulator what the bench measures' % name)
    rospy.init_node(name, anonymous=True, disable_signals=True)


def running_controllers():
    import rospy
    from controller_manager_msgs.srv import ListControllers
    try:
        reply = rospy.ServiceProxy(LIST_CONTROLLERS, ListControllers)()
    except Exception:  # not served yet
        return 0
    return sum(1 for c in reply.controller if c.state == 'running')


def wait_controllers(proc, timeout=120.0):
    common.wait_for(lambda: running_controllers() >= len(common.CONTROLLERS), timeout,
                    'the seven controllers', proc, period=0.02)


def node_pid(name, port):
    import rosgraph
    master = rosgraph.Master('/racebot_bench', master_uri='http://localhost:%d' % port)
    code, _, pid = xmlrpc.client.ServerProxy(master.lookupNode(name)).getPid('/racebot_bench')
    if code != 1:
        raise BenchError('could not get the pid of %s' % name)
    return int(pid)


class GazeboClient:
    """The /gazebo services the bench uses (a client of the world server's)."""

    def __init__(self):
        import rospy
        from gazebo_msgs.srv import GetWorldProperties
        from std_srvs.srv import Empty
        rospy.wait_for_service('/gazebo/get_world_properties', 60)
        self._props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties, persistent=True)
        self.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        self.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        self.reset = rospy.ServiceProxy('/gazebo/reset_simulation', Empty)

    def time(self):
        return self._props().sim_time


def measure_window(world, pid, seconds):
    """Real-time factor and CPU share (of one core) of the simulator over `seconds` of wall time."""
    s0, c0, w0 = world.time(), common.cpu_seconds(pid), time.perf_counter()
    time.sleep(seconds)
    s1, c1, w1 = world.time(), common.cpu_seconds(pid), time.perf_counter()
    return {'rtf': (s1 - s0) / (w1 - w0), 'cpu': (c1 - c0) / (w1 - w0), 'wall_s': w1 - w0, 'sim_s': s1 - s0}

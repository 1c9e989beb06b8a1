"""gazebo_ros's world control services: pause_physics, unpause_physics, reset_simulation, reset_world.

Each is the Simulator's: a pause takes effect under the step lock, so once pause_physics has answered no
world update starts (as Gazebo's World::SetPaused); reset_world puts poses, velocities and joints back to the
start and time goes on, reset_simulation also sets the time back to 0 (engine/simulator.py).
"""
from std_srvs.srv import Empty, EmptyResponse

from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup


class WorldControl(ServiceGroup):
    """The four std_srvs/Empty services that pause and reset the world."""

    SERVICES = dict.fromkeys(('pause_physics', 'unpause_physics', 'reset_simulation', 'reset_world'), Empty)

    def pause_physics(self, _req):
        self.sim.set_paused(True)
        return EmptyResponse()

    def unpause_physics(self, _req):
        self.sim.set_paused(False)
        return EmptyResponse()

    def reset_simulation(self, _req):
        self.sim.reset_simulation()
        return EmptyResponse()

    def reset_world(self, _req):
        self.sim.reset_world()
        return EmptyResponse()

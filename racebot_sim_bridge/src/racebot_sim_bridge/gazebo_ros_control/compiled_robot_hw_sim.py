"""A package's own RobotHWSim: gazebo_ros_control's <robotSimType> other than DefaultRobotHWSim, in C++.

The controller_host module (src/cpp/controller_host.cpp) makes the class through pluginlib and calls its initSim
with what gazebo_ros_control gives it: the robot's namespace and a NodeHandle there, the model (racebot's Gazebo 11
plugin API, whose joints are the simulated ones), the URDF from the `robotParam` parameter and its transmissions.
Then the control loop is upstream's: readSim and the controller manager's update each control period, writeSim
every world update. The C++ controllers use the RobotHWSim's handles; the Python ones (joint_state_controller, ...)
the mirror here (MirroredRobotHW): Python joint handles that readSim's states are copied into and whose commands go
back before writeSim.
"""
from racebot_sim_bridge.ros_control.hardware_interface import STATE, JointHandle, RobotHW


class RobotHWSimError(RuntimeError):
    """The RobotHWSim could not be made or its initSim failed; the message says why."""


class MirroredRobotHW(RobotHW):
    """The joints of a compiled RobotHWSim as the Python controllers see them: one handle per joint of its
    JointStateInterface, with the command interface it offers the joint through (the first, if several), or
    STATE for a joint it only reports. Kinds and limits are the URDF's where the joint is there (a RobotHWSim
    may add joints of its own)."""

    def __init__(self, model, joints):
        self.model = model
        self.handles = {}
        self.warnings = []
        for name, interfaces in joints:
            joint = model.joints.get(name)
            lim = joint.limit if joint is not None else None
            kind = joint.type if joint is not None and joint.type in ('revolute', 'prismatic') else 'continuous'
            self.handles[name] = JointHandle(name, kind, interfaces[0] if interfaces else STATE,
                                             lower=lim.lower if lim else None, upper=lim.upper if lim else None,
                                             max_effort=lim.effort if lim else None,
                                             max_velocity=lim.velocity if lim else None)
        self.names = sorted(self.handles)


class CompiledControlLoop:
    """gazebo_ros_control's Update() around a compiled RobotHWSim: the Simulator's ControlHook `cm`. Each control
    period, readSim with the time since the last one, then the controller manager's update."""

    def __init__(self, host, manager):
        self.host, self.manager = host, manager

    def update(self, time, period):
        self.host.read_sim(time, period)
        self.manager.update(time, period)

    def shutdown(self):
        self.manager.shutdown()
        self.host.close()


def load_robot_hw_sim(host, robot_sim_type, ns, robot_param, model_capsule, model):
    """initSim of `robot_sim_type` on `host` (a controller_host.Host without joints of its own); the mirror
    (MirroredRobotHW), bound to the host. RobotHWSimError saying why when it fails."""
    try:
        joints = host.init_sim(robot_sim_type, ns or '/', robot_param, model_capsule)
    except RuntimeError as err:
        raise RobotHWSimError(str(err)) from None
    mirror = MirroredRobotHW(model, joints)
    host.bind_mirror([(n, mirror.handles[n].interface if mirror.handles[n].interface != STATE else '',
                       mirror.handles[n]) for n in mirror.names])
    return mirror

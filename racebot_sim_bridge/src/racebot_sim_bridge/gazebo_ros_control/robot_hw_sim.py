"""gazebo_ros_control's DefaultRobotHWSim: the RobotHW of one spawned robot, on its PyBullet body.

initSim's rules: one joint per transmission with its first hardware interface (hardware_joints), PID gains
for position and velocity joints from `<ns>/gazebo_ros_control/pid_gains/<joint>` (pid_gains). readSim and
writeSim (read_sim, write_sim) run every world update for every robot: what they pass PyBullet is built
once here, and the per-joint work is in ros_control's compiled hardware_interface and pid.
"""
from racebot_sim_bridge.description.urdf_model import UrdfError, normalise_interface
from racebot_sim_bridge.engine.simulator import SpawnError
from racebot_sim_bridge.ros_control.hardware_interface import (COMMAND_INTERFACES, EFFORT, POSITION, VELOCITY, RobotHW,
                                                               limited_efforts, position_error, read_joint_states)
from racebot_sim_bridge.ros_control.pid import Pid

DEFAULT_ROBOT_SIM_TYPE = 'gazebo_ros_control/DefaultRobotHWSim'


def hardware_joints(model, supported=COMMAND_INTERFACES):
    """The (joint name, hardware interface) pairs DefaultRobotHWSim registers for a RobotModel.

    One per transmission, in document order, following DefaultRobotHWSim::initSim: the
    transmission must have exactly one joint; the interface is the joint's first one, else
    the first actuator's (with a warning); transmissions with no interface, or one not in
    ``supported``, are skipped with a warning.  Warnings go to ``model.warnings`` (once).
    UrdfError when a transmission names a joint the model does not have.
    """
    def warn(message):
        if message not in model.warnings:
            model.warnings.append(message)

    result, seen = [], set()
    for transmission in model.transmissions:
        what = "transmission '%s'" % transmission.name
        if len(transmission.joints) != 1:
            warn('%s has %s; only transmissions with exactly one joint are supported; skipped'
                 % (what, 'no joint' if not transmission.joints else
                    '%d joints' % len(transmission.joints)))
            continue
        joint_name, interfaces = transmission.joints[0]
        if joint_name not in model.joints:
            raise UrdfError("%s names joint '%s', which does not exist; fix the name or add "
                            'the joint' % (what, joint_name))
        if not interfaces and transmission.actuators and transmission.actuators[0][1]:
            interfaces = transmission.actuators[0][1]
            warn("%s: the <hardwareInterface> belongs inside <joint name='%s'>, not "
                 '<actuator>; used anyway' % (what, joint_name))
        if not interfaces:
            warn("%s: joint '%s' has no <hardwareInterface>; not simulated by ros_control"
                 % (what, joint_name))
            continue
        if len(interfaces) > 1:
            warn("%s: joint '%s' has several hardware interfaces; only the first (%s) is used"
                 % (what, joint_name, interfaces[0]))
        interface = normalise_interface(interfaces[0])
        if interface not in supported:
            warn("%s: joint '%s' interface '%s' is not supported (supported: %s); skipped"
                 % (what, joint_name, interface, ', '.join(supported)))
            continue
        if joint_name in seen:
            warn("%s: joint '%s' already has a transmission; skipped" % (what, joint_name))
            continue
        seen.add(joint_name)
        result.append((joint_name, interface))
    return result


def pid_gains(get_params, log, model_name, robot_ns, joints):
    """{joint: Pid} for the position and velocity joints of `joints` (hardware_joints) whose
    `<ns>/gazebo_ros_control/pid_gains/<joint>` is set, as DefaultRobotHWSim reads them at spawn; gains that
    are set and wrong are warned about and the joint follows its command directly."""
    gains = {}
    for joint, interface in joints:
        if interface not in (POSITION, VELOCITY):
            continue
        where = '%s/gazebo_ros_control/pid_gains/%s' % (robot_ns, joint)
        params = get_params(where)
        if params is None:
            continue
        try:
            gains[joint] = Pid.from_params(params, where)
        except ValueError as err:
            log.warn('%s: %s; joint %s follows its command directly instead of through a PID'
                     % (model_name, err, joint))
    return gains


class DefaultRobotHWSim(RobotHW):
    """The joints of one robot's transmissions on its PyBullet body (physics.Model)."""

    def __init__(self, model, body, joints, gains=None):
        """joints: hardware_joints(model); gains: {joint: Pid} of position or velocity joints driven
        through a PID (pid_gains); the others follow their command directly. SpawnError when a
        transmission's joint is no movable joint of the body."""
        super().__init__(model, joints)
        missing = [n for n in self.handles if n not in body.joints]
        if missing:
            raise SpawnError('SpawnModel: Failure - joints %s of the transmissions are not movable joints of '
                             'the model' % missing)
        self.body = body
        self.joint_handles = [self.handles[n] for n in self.names]
        self.indices = [body.joints[h.name].index for h in self.joint_handles]
        # A URDF <mimic> joint follows its leader (engine/mimic_joints.py): read, never commanded.
        for h in self.joint_handles:
            if h.name in body.mimics:
                c = body.mimics[h.name]
                self.warnings.append("joint '%s' is a URDF <mimic> of '%s' (racebot holds it at %g * %s %s %g; Gazebo "
                                     "ignores <mimic>): its state is read, the commands its controller writes are "
                                     "not applied" % (h.name, c.leader, c.multiplier, c.leader,
                                                      '-' if c.offset < 0 else '+', abs(c.offset)))
        commanded = [h for h in self.joint_handles if h.name not in body.mimics]
        self.effort_handles = [h for h in commanded if h.interface == EFFORT]
        self.effort_idx = [body.joints[h.name].index for h in self.effort_handles]
        gains = gains or {}
        # POSITION_PID / VELOCITY_PID joints: effort = PID(error), clamped to the effort limit, applied
        # as a force (writeSim, every world update).
        self.pid_joints = [(h, gains[h.name], body.joints[h.name].index) for h in commanded
                           if h.interface in (POSITION, VELOCITY) and h.name in gains]
        velocity = [h for h in commanded if h.interface == VELOCITY and h.name not in gains]
        position = [h for h in commanded if h.interface == POSITION and h.name not in gains]
        # What write_sim passes every step, built once.
        self._drives = [(hs, drive, [body.joints[h.name].index for h in hs], [h.max_effort or 1e3 for h in hs])
                        for hs, drive in ((velocity, 'drive_velocities'), (position, 'drive_positions')) if hs]

    def read_sim(self, world):
        """readSim: one PyBullet call for all joints; raw tuples (position, velocity, ...), no per-joint objects."""
        if self.joint_handles:
            read_joint_states(self.joint_handles, self.body.joint_states_raw(self.indices))

    def write_sim(self, world, dt):
        """writeSim: `dt` is the time since the last write (one world update)."""
        if not self.joint_handles:
            return
        if self.pid_joints:
            efforts = [self._pid_effort(h, pid, dt) for h, pid, _ in self.pid_joints]
            self.body.apply_efforts([i for _, _, i in self.pid_joints], efforts)
        if self.effort_handles:
            self.body.apply_efforts(self.effort_idx, limited_efforts(self.effort_handles))
        for hs, drive, indices, forces in self._drives:
            getattr(self.body, drive)(indices, [h.limited_command() for h in hs], forces)

    @staticmethod
    def _pid_effort(h, pid, dt):
        target = h.limited_command()
        if h.interface == VELOCITY:
            error = target - h.velocity
        else:
            error = position_error(h, target)
        effort = pid.compute(error, dt)
        if h.max_effort is not None:
            effort = min(max(effort, -h.max_effort), h.max_effort)
        h.effort = effort
        return effort

    def reset_joint_readings(self, world):
        """After the joints were moved from outside (set_model_configuration): readings start again
        from where the joints are, commands at 0."""
        if self.joint_handles:
            for h, s in zip(self.joint_handles, self.body.joint_states(self.indices)):
                h.reset_position(s.position)
            self.reset_commands()

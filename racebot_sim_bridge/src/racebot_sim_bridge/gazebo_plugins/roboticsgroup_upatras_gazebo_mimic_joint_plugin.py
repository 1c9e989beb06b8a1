"""libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so (roboticsgroup_upatras_gazebo_plugins 0.2.0; before its
rename, libroboticsgroup_gazebo_mimic_joint_plugin.so): mimicJoint made to follow joint * multiplier + offset.

Parameters as upstream's MimicJointPlugin::Load: joint and mimicJoint (required, else refused), multiplier (1),
offset (0), sensitiveness (0: act when |target - position| >= it), maxEffort (default the mimic joint's URDF
effort limit), robotNamespace (''), hasPID (present: PID mode; its text the gains' namespace, empty:
gazebo_ros_control/pid_gains/<mimicJoint>, under robotNamespace). Every world update (WorldUpdateBegin):
- without hasPID the mimic joint is put at the target (Joint::SetPosition, keeping its velocity), and at load its
  joint motor gets maxEffort as its force (ODE's fmax: a motor holding velocity 0, which brakes it between updates);
- with hasPID an effort PID(target - position) over the physics step, clamped to +-maxEffort, is applied to it.
The plugin takes the joint over from racebot's own URDF <mimic> gear (engine/mimic_joints.py), as in Gazebo the
plugin alone moves it. No Reset, no topics, as upstream. A maxEffort of 0 or less (a joint without an effort limit)
is no bound here (upstream's clamp with a negative limit gives a constant effort).
"""
import math

from racebot_sim_bridge.engine import mimic_joints
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.ros_control.pid import Pid


class MimicJointPlugin(ModelPlugin):
    libraries = ('libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so',
                 'libroboticsgroup_gazebo_mimic_joint_plugin.so')

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        p = self.params
        for tag, what in (('joint', 'joint'), ('mimicJoint', 'mimicJoint')):
            if not p.has(tag):
                raise PluginError('No %s element present. MimicJointPlugin could not be loaded' % what)
        self.leader = self.joint('joint')
        self.mimic = self.joint('mimicJoint')
        self.multiplier = p.number('multiplier', 1.0)
        self.offset = p.number('offset', 0.0)
        self.sensitiveness = p.number('sensitiveness', 0.0)
        limit = self.mimic.max_effort if self.mimic.max_effort > 0 else math.inf
        self.max_effort = p.number('maxEffort', limit)
        if not self.max_effort > 0:
            self.max_effort = math.inf
        self.pid = None
        if p.has('hasPID'):
            ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                        robot.name, ctx.sim.node_namespace)
            where = name_in(ns, p.string('hasPID', '') or 'gazebo_ros_control/pid_gains/' + self.mimic.name)
            try:
                self.pid = Pid.from_params(ctx.sim.get_params(where), where)
            except ValueError as err:  # control_toolbox's Pid::init fails: its gains stay 0, the effort too
                self.ctx.rospy.logerr('%s: %s; the PID has no gains, so the mimic joint gets no effort, as upstream'
                                      % (self.label, err))
                self.pid = Pid(0.0)
        body = robot.body
        if mimic_joints.release(self.world.client, body.mimics, self.mimic.name) is not None:
            self.info("joint '%s' is also a URDF <mimic>: this plugin drives it, racebot's own <mimic> gear is off"
                      % self.mimic.name)
        if self.pid is None and math.isfinite(self.max_effort):  # SetParam("fmax", 0, maxEffort)
            self.mimic.drive_velocity(0.0, self.max_effort)
        self.indices = [self.leader.index, self.mimic.index]
        self.info('MimicJointPlugin loaded! Joint: "%s", Mimic joint: "%s", Multiplier: %g, Offset: %g, MaxEffort: %g, '
                  'Sensitiveness: %g' % (self.leader.name, self.mimic.name, self.multiplier, self.offset,
                                         self.max_effort, self.sensitiveness))

    def before_physics(self, time):
        (leader, _), (position, velocity) = [s[:2] for s in self.robot.body.joint_states_raw(self.indices)]
        target = leader * self.multiplier + self.offset
        if abs(target - position) < self.sensitiveness:
            return
        if self.pid is None:
            self.mimic.set_position(target, velocity)
            return
        effort = self.pid.compute(target - position, self.world.step_size)
        self.mimic.apply_effort(min(max(effort, -self.max_effort), self.max_effort))

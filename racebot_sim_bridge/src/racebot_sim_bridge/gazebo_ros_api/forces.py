"""gazebo_ros's force services: apply_body_wrench, apply_joint_effort, clear_body_wrenches, clear_joint_forces.

As gazebo_ros_api_plugin (noetic) does it:
- a request becomes a job (target, value, start, duration); start is the request's start_time or, if that
  is earlier, the sim time now; a negative duration lasts until the clear_* service removes the job;
- every world update, with t the sim time the step ends at (Gazebo's time at WorldUpdateBegin), a job
  with start <= t <= start + duration (or a negative duration) is applied; once t > start + duration
  it is dropped. Times are compared in integer nanoseconds, as ros::Time compares them;
- a wrench is a world-frame force at the link's centre of mass and a world-frame torque (Link::SetForce
  and SetTorque). SetForce replaces: of several wrenches due on one link, the newest applies;
- a joint effort is added to what the joint's controller commands (Joint::SetForce accumulates), each
  request truncated as Joint::CheckAndTruncateForce does (effort limit; none in the direction of motion
  beyond the velocity limit);
- the wrench is moved to the body when it is asked for: `reference_point` x force is added to the
  torque, then from `reference_frame`'s origin to the link's (frame pose minus link pose, upstream's
  transformWrench), and those numbers are applied as world vectors from then on: exactly upstream's
  arithmetic, so a script gets the motion it gets in Gazebo. The empty name, `world`, `map` and `/map`
  (when no entity has that name) are the world frame;
- clear_joint_forces matches a joint's plain name, clear_body_wrenches a link's scoped name
  (`model::link`), in every model; reset_world and reset_simulation leave the jobs alone.

The schedule and the wrench arithmetic are plain Python (ForceSchedule, shift_wrench, wrench_in_link);
GazeboForces is the ROS service layer over a Simulator.
"""
import math
from collections import namedtuple

from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.kinematics.rotations import compose, inverse, rotate
from racebot_sim_bridge.engine.sim_time import to_ns
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup


# times in ns; duration < 0: until cleared; owner: the Model the target belongs to (a model deleted and
# spawned again under the same name is another body, which the old jobs do not touch)
Job = namedtuple('Job', 'target value start duration owner')


def job_due(job, t):
    return job.start <= t and (job.duration < 0 or t <= job.start + job.duration)


def job_over(job, t):
    return job.duration >= 0 and t > job.start + job.duration


class ForceSchedule:
    """Wrench jobs (target: (model, link), value: (force, torque)) and effort jobs (target: (model,
    joint), value: effort), in the order they came. Not thread-safe: the caller holds its lock."""

    def __init__(self):
        self.wrenches = []
        self.efforts = []

    def add_wrench(self, link, force, torque, start, duration, owner=None):
        self.wrenches.append(Job(link, (tuple(force), tuple(torque)), start, duration, owner))

    def add_effort(self, joint, effort, start, duration, owner=None):
        self.efforts.append(Job(joint, effort, start, duration, owner))

    def due(self, t):
        """What to apply in the update ending at t (ns): ({link: (force, torque, owner)},
        [(joint, effort, owner)]); jobs that are over are dropped."""
        wrenches = {}
        for job in self.wrenches:
            if job_due(job, t):
                wrenches[job.target] = job.value + (job.owner,)  # SetForce/SetTorque replace: the newest wins
        efforts = [(job.target, job.value, job.owner) for job in self.efforts if job_due(job, t)]
        self.wrenches = [j for j in self.wrenches if not job_over(j, t)]
        self.efforts = [j for j in self.efforts if not job_over(j, t)]
        return wrenches, efforts

    def clear_wrenches(self, matches):
        """Drops the wrench jobs whose target `matches`; returns how many."""
        before = len(self.wrenches)
        self.wrenches = [j for j in self.wrenches if not matches(j.target)]
        return before - len(self.wrenches)

    def clear_efforts(self, matches):
        before = len(self.efforts)
        self.efforts = [j for j in self.efforts if not matches(j.target)]
        return before - len(self.efforts)

    def drop_orphans(self, alive):
        """Drops the jobs whose owner is no longer `alive(owner)` (a deleted model's)."""
        self.wrenches = [j for j in self.wrenches if alive(j.owner)]
        self.efforts = [j for j in self.efforts if alive(j.owner)]


def start_and_duration(start_ns, duration_ns, now_ns):
    """Upstream's job times: a start before now starts now."""
    return max(start_ns, now_ns), duration_ns


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def shift_wrench(force, torque, point):
    """A wrench given at `point` as one about the frame's origin: the torque gains point x force."""
    return tuple(force), tuple(t + m for t, m in zip(torque, cross(point, force)))


def wrench_in_link(force, torque, frame_pose, link_pose):
    """upstream's transformWrench: a wrench about frame F's origin in F's axes, as one about the link's
    origin in the link's axes. Poses are (xyz, quaternion xyzw) pairs in the world."""
    offset, turn = compose(inverse(link_pose), frame_pose)  # F in the link's frame (ignition F - link)
    f = rotate(turn, force)
    t = rotate(turn, torque)
    return f, tuple(a + b for a, b in zip(t, cross(offset, f)))


def truncate_effort(effort, velocity, effort_limit, velocity_limit):
    """Joint::CheckAndTruncateForce: no push beyond the velocity limit, then clamp to the effort
    limit. A limit <= 0 (a URDF joint without one) does not truncate."""
    if velocity_limit > 0:
        if velocity > velocity_limit and effort > 0:
            effort = 0.0
        elif velocity < -velocity_limit and effort < 0:
            effort = 0.0
    if effort_limit > 0:
        effort = max(-effort_limit, min(effort_limit, effort))
    return effort


class GazeboForces(ServiceGroup):
    """The four force services' handlers, and the simulator hook that applies the jobs."""

    SERVICES = {'apply_body_wrench': 'ApplyBodyWrench', 'apply_joint_effort': 'ApplyJointEffort',
                'clear_body_wrenches': 'BodyRequest', 'clear_joint_forces': 'JointRequest'}

    def __init__(self, rospy, sim):
        super().__init__(rospy, sim)
        self.schedule = ForceSchedule()

    # -- services ---------------------------------------------------------------------------------
    def apply_body_wrench(self, req):
        res = self.srv.ApplyBodyWrenchResponse()
        f, t, p = req.wrench.force, req.wrench.torque, req.reference_point
        with self.sim.lock:
            link = self._link(req.body_name)
            if link is None:
                return self.fail(res, 'ApplyBodyWrench: body does not exist',
                                 'ApplyBodyWrench: body [%s] does not exist' % req.body_name)
            if not frames.finite(f.x, f.y, f.z, t.x, t.y, t.z, p.x, p.y, p.z):
                return self.fail(res, 'ApplyBodyWrench: wrench and reference_point must be finite numbers, got '
                                      'force (%g, %g, %g), torque (%g, %g, %g), point (%g, %g, %g)'
                                      % (f.x, f.y, f.z, t.x, t.y, t.z, p.x, p.y, p.z))
            force, torque = shift_wrench((f.x, f.y, f.z), (t.x, t.y, t.z), (p.x, p.y, p.z))
            frame = self.entities.resolve(req.reference_frame)
            if frame is not None:
                link_pose = self.entities.state(frames.Entity(*link))[0]
                force, torque = wrench_in_link(force, torque, self.entities.state(frame)[0], link_pose)
            elif not frames.is_world_frame(req.reference_frame):
                return self.fail(res, 'ApplyBodyWrench: reference_frame not found',
                                 'ApplyBodyWrench: reference_frame is not a valid entity name')
            start, duration = start_and_duration(req.start_time.to_nsec(), req.duration.to_nsec(), self._now())
            self.schedule.add_wrench(link, force, torque, start, duration, self.sim.world.bodies[link[0]])
            self.sim.set_step_hook('before_physics', self.apply, True, first=True)
        res.success, res.status_message = True, ''  # upstream says nothing on success
        return res

    def apply_joint_effort(self, req):
        res = self.srv.ApplyJointEffortResponse()
        with self.sim.lock:
            joint = self._joint(req.joint_name)
            if joint is None:
                return self.fail(res, 'ApplyJointEffort: joint not found',
                                 'ApplyJointEffort: joint [%s] not found (movable joints: %s)' % (
                                     req.joint_name, ', '.join(sorted(j for b in self.sim.world.bodies.values()
                                                                      for j in b.joints)) or 'none'))
            if not math.isfinite(req.effort):
                return self.fail(res, 'ApplyJointEffort: effort must be a finite number, got %r' % req.effort)
            start, duration = start_and_duration(req.start_time.to_nsec(), req.duration.to_nsec(), self._now())
            self.schedule.add_effort(joint, req.effort, start, duration, self.sim.world.bodies[joint[0]])
            self.sim.set_step_hook('before_physics', self.apply, True, first=True)
        res.success, res.status_message = True, 'ApplyJointEffort: effort set'
        return res

    def clear_body_wrenches(self, req):
        with self.sim.lock:
            n = self.schedule.clear_wrenches(lambda target: '%s::%s' % target == req.body_name)
        if not n:
            self.rospy.logwarn("clear_body_wrenches: no wrench on a body named '%s'; bodies are cleared by their "
                               "scoped name, model::link" % req.body_name)
        return self.srv.BodyRequestResponse()

    def clear_joint_forces(self, req):
        with self.sim.lock:
            n = self.schedule.clear_efforts(lambda target: target[1] == req.joint_name)
        if not n:
            self.rospy.logwarn("clear_joint_forces: no effort on a joint named '%s'; joints are cleared by their "
                               "plain name, as apply_joint_effort names them in the URDF" % req.joint_name)
        return self.srv.JointRequestResponse()

    # -- the world update -------------------------------------------------------------------------
    def apply(self, time):
        """Simulator.before_physics while there are jobs: those due in the update ending at `time` (s)."""
        if not (self.schedule.wrenches or self.schedule.efforts):
            self.sim.set_step_hook('before_physics', self.apply, False)
            return
        world = self.sim.world
        self.schedule.drop_orphans(lambda body: world.bodies.get(body.name) is body)
        wrenches, efforts = self.schedule.due(to_ns(time))
        for (_, link), (force, torque, body) in wrenches.items():
            body.links[link].apply_wrench(force, torque)
        for (_, joint), effort, body in efforts:
            info = body.joints[joint]
            info.apply_effort(truncate_effort(effort, info.state().velocity, info.max_effort, info.max_velocity))

    # -- names ------------------------------------------------------------------------------------
    def _now(self):
        return to_ns(self.sim.time)

    def _link(self, name):
        """(model, link) of the link Gazebo's EntityByName finds under `name`; None for a model or nothing."""
        entity = self.entities.find_link(name)
        return None if entity is None else (entity.model, entity.link)

    def _joint(self, name):
        """(model, joint) as Model::GetJoint finds it, model by model: the plain or scoped name."""
        body, joint = self.entities.find_joint(name)
        return None if body is None else (body.name, joint)


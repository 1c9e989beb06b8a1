"""gazebo_ros's joint property services: get_joint_properties, set_joint_properties.

As upstream, get_joint_properties reports every joint as REVOLUTE with no damping (its FIXME). set_joint_properties:
damping, hiStop/loStop (limits) and fmax/vel (ODE's joint motor: a velocity target held with at most fmax) act on
the joint; erp, cfm, stop_erp, stop_cfm and fudge_factor have no PyBullet counterpart: accepted, logged once,
reported back by nothing. A joint is found as Model::GetJoint finds it, model by model: plain or scoped name.
"""
from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup, refused


class JointProperties(ServiceGroup):
    """get_joint_properties and set_joint_properties over a Simulator; the joint motors set_joint_properties left."""

    SERVICES = {'get_joint_properties': 'GetJointProperties', 'set_joint_properties': 'SetJointProperties'}

    # ODE joint parameters that PyBullet has no counterpart for.
    IGNORED_JOINT_PARAMS = ('erp', 'cfm', 'stop_erp', 'stop_cfm', 'fudge_factor')

    def __init__(self, rospy, sim):
        super().__init__(rospy, sim)
        self.motors = {}  # (model, joint) -> (Model, vel, fmax): ODE's joint motor as set_joint_properties left it
        self._warned = set()

    def get_joint_properties(self, req):
        res = self.srv.GetJointPropertiesResponse()
        with self.sim.lock:
            body, joint = self.entities.find_joint(req.joint_name)
            if body is None:
                return refused(res, 'GetJointProperties: joint not found')
            state = body.joints[joint].state()
        res.type = res.REVOLUTE  # upstream's FIXME: every joint is reported revolute, damping empty
        res.damping = []
        res.position = [state.position]
        res.rate = [state.velocity]
        res.success, res.status_message = True, 'GetJointProperties: got properties'
        return res

    def set_joint_properties(self, req):
        res = self.srv.SetJointPropertiesResponse()
        c = req.ode_joint_config
        lists = dict(damping=c.damping, hiStop=c.hiStop, loStop=c.loStop, erp=c.erp, cfm=c.cfm,
                     stop_erp=c.stop_erp, stop_cfm=c.stop_cfm, fudge_factor=c.fudge_factor, fmax=c.fmax, vel=c.vel)
        with self.sim.lock:
            body, joint = self.entities.find_joint(req.joint_name)
            if body is None:
                return self.fail(res, 'SetJointProperties: joint not found')
            bad = [k for k, v in lists.items() if not frames.finite(*v)]
            if bad:
                return self.fail(res, 'SetJointProperties: %s of joint [%s] must be finite numbers'
                                 % (', '.join(bad), req.joint_name))
            first = {k: v[0] for k, v in lists.items() if len(v)}
            info = body.joints[joint]
            lower, upper = first.get('loStop', info.lower), first.get('hiStop', info.upper)
            if lower > upper:
                return self.fail(res, 'SetJointProperties: loStop %g is above hiStop %g for joint [%s]'
                                 % (lower, upper, req.joint_name))
            if first.get('damping', 0.0) < 0 or first.get('fmax', 0.0) < 0:
                return self.fail(res, 'SetJointProperties: damping and fmax of joint [%s] must be >= 0'
                                 % req.joint_name)
            extra = sorted(k for k, v in lists.items() if len(v) > 1)
            ignored = sorted(k for k in self.IGNORED_JOINT_PARAMS if k in first)
            info.set_dynamics(damping=first.get('damping'), lower=first.get('loStop'), upper=first.get('hiStop'))
            if 'fmax' in first or 'vel' in first:
                owner, vel, fmax = self.motors.get((body.name, joint), (body, 0.0, 0.0))
                if owner is not body:  # the model was deleted and spawned again: its motor starts off
                    vel, fmax = 0.0, 0.0
                vel, fmax = first.get('vel', vel), first.get('fmax', fmax)
                self.motors[(body.name, joint)] = (body, vel, fmax)
                info.drive_velocity(vel, fmax)
        for what in ([('axes beyond the first (%s): the joints here have one' % ', '.join(extra))] if extra else []) + \
                ([('%s: ODE parameters with no PyBullet counterpart' % ', '.join(ignored))] if ignored else []):
            if what not in self._warned:
                self._warned.add(what)
                self.rospy.logwarn('set_joint_properties: %s are ignored' % what)
        res.success, res.status_message = True, 'SetJointProperties: properties set'
        return res

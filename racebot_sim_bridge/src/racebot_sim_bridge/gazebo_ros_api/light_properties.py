"""gazebo_ros's light services: get_light_properties, set_light_properties, delete_light.

The lights are the world's (<light> and model://sun of the world file): live state (Simulator.lights, as the
physics settings are the Simulator's and its PhysicsWorld's; the world file's description is never written) that
these services read, change and delete. Nothing is lit by them here (the cameras do not shade by them). As
upstream, the services say nothing on success (delete_light aside).
"""
import dataclasses
import threading

from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup, refused
from racebot_sim_bridge.kinematics.rotations import quaternion_to_rpy


class LightProperties(ServiceGroup):
    """The three light services over a Simulator's lights."""

    SERVICES = {'get_light_properties': 'GetLightProperties', 'set_light_properties': 'SetLightProperties',
                'delete_light': 'DeleteLight'}

    def __init__(self, rospy, sim):
        super().__init__(rospy, sim)
        self._lock = threading.Lock()

    def _light(self, res, name, service):
        """The light called `name`; None when there is none, `res` then refused in upstream's words (`service`:
        the name its message starts with). Caller holds the lock."""
        light = next((light for light in self.sim.lights if light.name == name), None)
        if light is None:
            refused(res, '%s: Requested light %s not found!' % (service, name))
        return light

    def get_light_properties(self, req):
        res = self.srv.GetLightPropertiesResponse()
        with self._lock:
            light = self._light(res, req.light_name, 'getLightProperties')
            if light is None:
                return res
            res.diffuse.r, res.diffuse.g, res.diffuse.b, res.diffuse.a = light.diffuse
            _, res.attenuation_constant, res.attenuation_linear, res.attenuation_quadratic = light.attenuation
        res.success = True  # upstream leaves status_message empty
        return res

    def set_light_properties(self, req):
        res = self.srv.SetLightPropertiesResponse()
        d, s, p, q = req.diffuse, req.specular, req.pose.position, req.pose.orientation
        values = (d.r, d.g, d.b, d.a, s.r, s.g, s.b, s.a, req.attenuation_constant, req.attenuation_linear,
                  req.attenuation_quadratic, req.direction.x, req.direction.y, req.direction.z, p.x, p.y, p.z,
                  q.x, q.y, q.z, q.w)
        with self._lock:
            light = self._light(res, req.light_name, 'setLightProperties')
            if light is None:
                return res
            if not frames.finite(*values):
                return self.fail(res, 'setLightProperties: colours, attenuation, direction and pose of light %s '
                                      'must be finite' % req.light_name)
            orientation = frames.normalised((q.x, q.y, q.z, q.w))
            index = self.sim.lights.index(light)
            self.sim.lights[index] = dataclasses.replace(
                light, cast_shadows=bool(req.cast_shadows), diffuse=(d.r, d.g, d.b, d.a),
                specular=(s.r, s.g, s.b, s.a),
                attenuation=(light.attenuation[0], req.attenuation_constant, req.attenuation_linear,
                             req.attenuation_quadratic),
                direction=(req.direction.x, req.direction.y, req.direction.z),
                pose=(p.x, p.y, p.z) + tuple(quaternion_to_rpy(orientation)))
        res.success = True  # upstream leaves status_message empty
        return res

    def delete_light(self, req):
        res = self.srv.DeleteLightResponse()
        with self._lock:
            light = self._light(res, req.light_name, 'DeleteLight')
            if light is None:
                return res
            self.sim.lights.remove(light)
        res.success, res.status_message = True, 'DeleteLight: %s successfully deleted' % req.light_name
        return res

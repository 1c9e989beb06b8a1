"""gazebo_ros's get_model_properties: a model's links, collisions and joints as Gazebo names them.

A URDF model's links are those Gazebo keeps after fixed-joint lumping, its collisions named as sdformat's
parser_urdf names them (urdf_geom_names), its joints those not lumped away; an SDF model's links and collisions
are its own.
"""
from racebot_sim_bridge.engine.physics_types import BodyKind
from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities
from racebot_sim_bridge.gazebo_ros_api.service_group import ServiceGroup

# Gazebo's names for a URDF link's collisions after fixed-joint lumping (sdformat's parser_urdf).
LUMP_PREFIX = '_fixed_joint_lump__'
COLLISION_SUFFIX = '_collision'


def urdf_geom_names(model, link):
    """Gazebo's collision names of a (lumped) URDF link: its own, then those of the links merged into
    it, `L_collision`, `L_fixed_joint_lump__C_collision`, the n-th (n >= 1) with `_n` added."""
    merged = [link] + [name for name in model.links if name != link and model.lumped_link(name) == link]
    names = []
    for name in merged:
        stem = link if name == link else link + LUMP_PREFIX + name
        for _ in model.links[name].collisions:
            n = len(names)
            names.append(stem + COLLISION_SUFFIX + ('_%d' % n if n else ''))
    return names


class ModelProperties(ServiceGroup):
    """get_model_properties over a Simulator."""

    SERVICES = {'get_model_properties': 'GetModelProperties'}

    def get_model_properties(self, req):
        res = self.srv.GetModelPropertiesResponse()
        with self.sim.lock:
            body = self.sim.world.bodies.get(req.model_name)
            if body is None:
                return self.fail(res, 'GetModelProperties: model does not exist',
                                 'GetModelProperties: model [%s] does not exist' % req.model_name)
            res.body_names = WorldEntities.link_names(body)
            kind, spec = body.source.kind, body.source.model
            if kind is BodyKind.URDF:
                res.geom_names = [g for link in res.body_names for g in urdf_geom_names(spec, link)]
                # Gazebo's joints: every URDF joint not lumped away (its child stays a link of its own)
                res.joint_names = [j.name for j in spec.joints.values() if spec.lumped_link(j.child) == j.child]
            else:
                res.geom_names = [c.name for link in spec.links for c in link.collisions]
            res.is_static = bool(body.static)
        res.success, res.status_message = True, 'GetModelProperties: got properties'
        return res

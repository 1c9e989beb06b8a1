"""A contact sensor's measurement: PyBullet's contact points of one link, with Gazebo's names.

Runs on the physics client after a step (callers hold the simulator's lock). PyBullet keeps the
contact points of the last step: getContactPoints(bodyA=robot, linkIndexA=link) gives each with
the normal on the other body pointing into ours, the distance (negative: penetration), the
normal force and two friction forces along their directions. A point counts as a contact when the
bodies touch (distance <= 0) or push (normal force > 0), as an ODE contact would.
The force on our link is normal force x normal + each friction force along its direction. PyBullet
turns the normal towards our link but not the friction directions: they are as Bullet keeps the
pair, so their sign is turned here when Bullet keeps the other body first (contact.friction_reversed,
from each side's creation order and shape: CollisionKinds read once per link).
"""
import numpy as np
import pybullet as pb

from racebot_sim_bridge.sensors.contact import (CollisionKind, ContactPoint, friction_reversed, group_contacts,
                                                nearest_shape, sdf_collision_shapes, urdf_collision_shapes)
from racebot_sim_bridge.engine.physics_types import BodyKind
from racebot_sim_bridge.kinematics.rotations import rotate_back


class CollisionNames:
    """Gazebo's full collision name (model::link::collision) of a PyBullet (body id, link index)
    and a point on it, over a physics.PhysicsWorld's bodies; shapes per link computed once."""

    def __init__(self, world):
        self.world = world
        self._shapes = {}   # (body id, link index) -> (model name, link name, [NamedShape])

    def _lookup(self, body_id, link_index):
        key = (body_id, link_index)
        found = self._shapes.get(key)
        if found is not None:
            return found
        for body in list(self.world.bodies.values()):
            if body.kind is BodyKind.SDF:
                model = body.source.model
                ids = [(next(iter(body.link_index)), body.id)] + list(body.extra_bodies)
                for link_name, bid in ids:
                    if bid == body_id:
                        link = next((lk for lk in model.links if lk.name == link_name), None)
                        found = (body.name, link_name, sdf_collision_shapes(link) if link else [])
            elif body.id == body_id:
                link_name = next((n for n, i in body.link_index.items() if i == link_index), None)
                if link_name is not None:
                    found = (body.name, link_name, urdf_collision_shapes(body.source.model, link_name))
            if found is not None:
                break
        if found is None:
            found = ('body%d' % body_id, 'link%d' % link_index, [])  # not one of the world's bodies
        self._shapes[key] = found
        return found

    def forget(self):
        """Drops what is known (bodies come and go: called when the world's bodies change)."""
        self._shapes.clear()

    def name(self, body_id, link_index, point):
        """model::link::collision of the collision of (body, link) nearest to world `point`."""
        model_name, link_name, shapes = self._lookup(body_id, link_index)
        if not shapes:
            return '%s::%s::%s%s' % (model_name, link_name, link_name, '_collision')
        if len(shapes) == 1:
            return '%s::%s::%s' % (model_name, link_name, shapes[0].name)
        position, orientation = link_frame(self.world.client, body_id, link_index)
        local = rotate_back(orientation, np.asarray(point) - position)
        return '%s::%s::%s' % (model_name, link_name, nearest_shape(shapes, local).name)


def link_frame(client, body_id, link_index):
    """World (position, quaternion) of a link's URDF frame (the base's too)."""
    if link_index < 0:
        pos, orn = client.getBasePositionAndOrientation(body_id)
        dyn = client.getDynamicsInfo(body_id, -1)
        inv_pos, inv_orn = pb.invertTransform(dyn[3], dyn[4])
        pos, orn = pb.multiplyTransforms(pos, orn, inv_pos, inv_orn)
        return np.asarray(pos), tuple(orn)
    s = client.getLinkState(body_id, link_index, computeForwardKinematics=1)
    return np.asarray(s[4]), tuple(s[5])


def link_com(client, body_id, link_index):
    """World (centre of mass, frame orientation) of a link."""
    if link_index < 0:
        pos, _ = client.getBasePositionAndOrientation(body_id)
        return np.asarray(pos), link_frame(client, body_id, -1)[1]
    s = client.getLinkState(body_id, link_index, computeForwardKinematics=1)
    return np.asarray(s[0]), tuple(s[5])


def collision_kind(client, body_id, link_index):
    """The CollisionKind of a body's link (see contact.friction_reversed)."""
    shapes = client.getCollisionShapeData(body_id, link_index)
    mass = client.getDynamicsInfo(body_id, link_index)[0]
    concave = bool(shapes) and all(s[2] == pb.GEOM_PLANE or (s[2] == pb.GEOM_MESH and mass == 0.0) for s in shapes)
    return CollisionKind((body_id, link_index), len(shapes) > 1, concave)


class CollisionKinds:
    """collision_kind per (body, link), read once; forget() when bodies change."""

    def __init__(self, client):
        self.client = client
        self._kinds = {}

    def __call__(self, body_id, link_index):
        key = (body_id, link_index)
        kind = self._kinds.get(key)
        if kind is None:
            kind = self._kinds[key] = collision_kind(self.client, body_id, link_index)
        return kind

    def forget(self):
        self._kinds.clear()


def read_contacts(world, names, body_id, link_index, shapes, model_name, link_name, wanted, kinds=None):
    """[ContactPoint] on (body_id, link_index) whose own collision (nearest of `shapes`, the
    link's NamedShapes) is in `wanted` (Gazebo collision names, without model::link::). `kinds`: a
    CollisionKinds of the world (made here when not given)."""
    points = world.client.getContactPoints(bodyA=body_id, linkIndexA=link_index)
    kinds = kinds if kinds is not None else CollisionKinds(world.client)
    if not points:
        return []
    frame = None
    out = []
    for p in points:
        distance, normal_force = p[8], p[9]
        if distance > 0.0 and normal_force <= 0.0:
            continue  # near, not touching
        own = shapes[0] if len(shapes) == 1 else None
        if own is None:
            if frame is None:
                frame = link_frame(world.client, body_id, link_index)
            own = nearest_shape(shapes, rotate_back(frame[1], np.asarray(p[5]) - frame[0]))
        if own is None or own.name not in wanted:
            continue
        normal = np.asarray(p[7], dtype=np.float64)
        friction = p[10] * np.asarray(p[11]) + p[12] * np.asarray(p[13])
        if friction_reversed(kinds(body_id, link_index), kinds(p[2], p[4])):
            friction = -friction
        force = normal_force * normal + friction
        out.append(ContactPoint('%s::%s::%s' % (model_name, link_name, own.name),
                                names.name(p[2], p[4], p[6]), tuple(p[5]), tuple(normal),
                                max(0.0, -distance), tuple(force)))
    return out


# Gazebo's ContactSensor keeps the contact messages (one a physics step) of at most the last 100 steps between updates
CONTACT_STEPS_KEPT = 100


class LinkContacts:
    """The contacts of a link's watched collisions, one physics step at a time, as a contact sensor reads them:
    read() gives this step's ContactGroups (contact.group_contacts: per pair of collisions, the wrench on the link
    in its frame about its centre of mass). `world`: the PhysicsWorld; `body_id`, `link_index`: the link in
    PyBullet; `shapes`: its NamedShapes; `model_name`, `link_name`: for the collisions' Gazebo names; `wanted`: the
    watched collision names (without model::link::)."""

    def __init__(self, world, body_id, link_index, shapes, model_name, link_name, wanted):
        self.world = world
        self.body_id, self.link_index = body_id, link_index
        self.shapes, self.model_name, self.link_name = shapes, model_name, link_name
        self.wanted = set(wanted)
        self.names = CollisionNames(world)
        self.kinds = CollisionKinds(world.client)
        self.bodies_seen = None

    def read(self):
        world = self.world
        bodies = tuple(id(b) for b in world.bodies.values())
        if bodies != self.bodies_seen:  # a body came or went: PyBullet ids may have been reused
            self.names.forget()
            self.kinds.forget()
            self.bodies_seen = bodies
        points = read_contacts(world, self.names, self.body_id, self.link_index, self.shapes, self.model_name,
                               self.link_name, self.wanted, self.kinds)
        if not points:
            return []
        com, orientation = link_com(world.client, self.body_id, self.link_index)
        return group_contacts(points, com, orientation)

"""The sensors' view of the PyBullet world: where a sensor is, what its rays hit, what it sees.

No rospy here. Every call takes the physics world (physics.PhysicsWorld) and runs on its client;
callers hold the simulator's lock.

- SensorMount: a sensor's pose on a spawned body. PyBullet merges fixed-joint links into their
  parent (as Gazebo does), so a sensor link such as `lidar` is no PyBullet link: the mount is the
  link it was merged into plus the fixed offset urdf_model computes, plus the sensor's <pose>.
- cast_rays: one rayTestBatch for all beams.
- render: PyBullet's CPU renderer (ER_TINY_RENDERER); there is no GPU.
- SceneColours: without a window the physics world makes no visual shapes, and the renderer
  draws each collision shape in a default grey (the ground plane with a checker texture). This
  gives world and spawned SDF models the colours their <visual><material> declares.
"""
import numpy as np
import pybullet as pb

from . import sdf_world

MAX_RAYS_PER_BATCH = 16384  # PyBullet's limit for one rayTestBatch call


class SensorMount(object):
    def __init__(self, world, body, model, reference, sensor_pose=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)):
        """`body`: physics.Body of the robot; `model`: its urdf_model.RobotModel; `reference`: the
        link named by <gazebo reference>; `sensor_pose`: the sensor's <pose> (x y z r p y) in it.
        Raises KeyError when the link it is merged into is not a PyBullet link of the body."""
        self.world = world
        self.body = body
        self.link = model.lumped_link(reference)
        if self.link not in body.link_index:
            raise KeyError("link %r (carrying %r) is not a link of the spawned body (links: %s)"
                           % (self.link, reference, ', '.join(sorted(body.link_index))))
        self.index = body.link_index[self.link]
        self.offset = sdf_world.compose(model.pose_in_lumped_link(reference), sensor_pose)

    def _link(self, velocity):
        """(frame position, frame orientation, COM position, linear velocity at the COM, angular
        velocity) of the carrying link, all in world coordinates."""
        client, body = self.world.client, self.body
        if self.index < 0:
            frame = body.frame_pose()
            com = body.pose()
            lin, ang = body.twist() if velocity else ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
            return frame.position, frame.orientation, com.position, lin, ang
        s = pb.getLinkState(body.id, self.index, computeLinkVelocity=1 if velocity else 0,
                            computeForwardKinematics=1, physicsClientId=client)
        lin, ang = (s[6], s[7]) if velocity else ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        return s[4], s[5], s[0], lin, ang

    def pose(self):
        """World (position, quaternion xyzw) of the sensor."""
        pos, orn, _, _, _ = self._link(False)
        p, q = pb.multiplyTransforms(pos, orn, self.offset[0], self.offset[1])
        return np.asarray(p), tuple(q)

    def motion(self):
        """(position, quaternion, world velocity of the sensor point, world angular velocity)."""
        pos, orn, com, lin, ang = self._link(True)
        p, q = pb.multiplyTransforms(pos, orn, self.offset[0], self.offset[1])
        p, omega = np.asarray(p), np.asarray(ang)
        velocity = np.asarray(lin) + np.cross(omega, p - np.asarray(com))
        return p, tuple(q), velocity, omega


def cast_rays(world, starts, ends):
    """(fractions along each segment, hit flags) for segments starts[i] -> ends[i] (N x 3)."""
    starts = np.asarray(starts, dtype=np.float64)
    ends = np.asarray(ends, dtype=np.float64)
    fractions = np.ones(len(starts))
    hit = np.zeros(len(starts), dtype=bool)
    for first in range(0, len(starts), MAX_RAYS_PER_BATCH):
        last = first + MAX_RAYS_PER_BATCH
        results = pb.rayTestBatch(starts[first:last], ends[first:last], numThreads=1,
                                  physicsClientId=world.client)
        fractions[first:last] = [r[2] for r in results]
        hit[first:last] = [r[0] >= 0 for r in results]
    return fractions, hit


def render(world, width, height, view_matrix, projection_matrix):
    """(rgb uint8 height x width x 3, depth buffer float32 height x width) from the CPU renderer."""
    w, h, rgba, depth, _ = pb.getCameraImage(width, height, view_matrix, projection_matrix, shadow=0,
                                             renderer=pb.ER_TINY_RENDERER, flags=pb.ER_NO_SEGMENTATION_MASK,
                                             physicsClientId=world.client)
    rgb = np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4)[:, :, :3]
    return rgb, np.asarray(depth, dtype=np.float32).reshape(h, w)


class GroundPlane(object):
    """An infinite plane the cameras draw themselves (see SceneColours)."""

    def __init__(self, body_key, point, normal, rgb):
        self.body_key = body_key
        self.point = np.asarray(point, dtype=np.float64)
        self.normal = np.asarray(normal, dtype=np.float64) / np.linalg.norm(normal)
        self.rgb = np.asarray(rgb, dtype=np.uint8)


class SceneColours(object):
    """Colours the bodies of SDF models as their visuals say (the first visual with a colour).

    Planes: the CPU renderer rasterises an infinite plane as huge triangles, which costs half of
    an 800 x 800 frame. Without a window, a world model's plane is therefore made invisible to the
    renderer and listed in `planes` with the colour the renderer gives it (measured once on a
    tiny image); cameras then draw it per pixel where it is nearer than what was rendered
    (sensors_camera.PinholeCamera.plane_depth), which gives the same picture for a fraction of
    the cost. With a window on this client the plane stays as it is (the window shows it).
    """

    def __init__(self, world):
        self.world = world
        self.planes = []
        self.done = set()  # (model name, body id) of the bodies already coloured

    def refresh(self, models=()):
        """Colours every SDF body not coloured yet: those that carry their sdf_world.Model
        (Body.source, as physics.PhysicsWorld records it) and those of `models`; forgets
        the planes of removed bodies."""
        world = self.world
        by_name = {m.name: m for m in models}
        for name, body in list(world.bodies.items()):
            key = (name, body.id)
            if key in self.done:
                continue
            source = getattr(body, 'source', None)
            model = source[1] if source and source[0] == 'sdf' else by_name.get(name)
            if model is not None:
                self.colour_model(model, body)
            self.done.add(key)
        alive = {(name, body.id) for name, body in world.bodies.items()}
        self.planes = [p for p in self.planes if p.body_key in alive]
        self.done &= alive

    def colour_model(self, model, body=None):
        """`model`: sdf_world.Model, already added to the world (its Body found by name)."""
        body = body if body is not None else self.world.bodies.get(model.name)
        if body is None:
            return
        ids = {name: body.id for name, index in body.link_index.items() if index == -1}
        ids.update(dict(getattr(body, 'extra_bodies', [])))
        for link in model.links:
            body_id = ids.get(link.name)
            if body_id is None:
                continue
            rgba = next((v.rgba for v in link.visuals if v.rgba), None)
            plane = next((c for c in link.collisions if c.shape.kind == 'plane'), None)
            if plane is None and (rgba is None or getattr(self.world, "visuals", False)):  # visuals: coloured when built
                continue
            kwargs = dict(rgbaColor=list(rgba or (0.8, 0.8, 0.8, 1.0)))
            if plane is not None:
                kwargs['textureUniqueId'] = -1  # PyBullet's checker texture is not the world's ground
            try:
                pb.changeVisualShape(body_id, -1, physicsClientId=self.world.client, **kwargs)
            except pb.error:
                continue  # a body without any drawable shape: nothing to colour
            if plane is not None and not self.world.gui:
                self._draw_analytically(model, link, plane, body_id, (model.name, body.id))

    def _draw_analytically(self, model, link, collision, body_id, body_key):
        position, orientation = model.world_pose_of(link, collision)
        normal = sdf_world.rotate(orientation, collision.shape.normal or (0.0, 0.0, 1.0))
        normal = np.asarray(normal) / np.linalg.norm(normal)
        point = np.asarray(position)
        # What the renderer draws for it: look at it from 1 cm away with a 1 degree field of view.
        eye = point + 0.01 * normal
        up = np.cross(normal, [1.0, 0.0, 0.0])
        if np.linalg.norm(up) < 1e-6:
            up = np.cross(normal, [0.0, 1.0, 0.0])
        client = self.world.client
        view = pb.computeViewMatrix(eye.tolist(), point.tolist(), up.tolist(), physicsClientId=client)
        proj = pb.computeProjectionMatrixFOV(1.0, 1.0, 0.001, 1.0, physicsClientId=client)
        rgb, _ = render(self.world, 4, 4, view, proj)
        colour = rgb[2, 2].copy()
        pb.changeVisualShape(body_id, -1, rgbaColor=[0.0, 0.0, 0.0, 0.0], physicsClientId=client)
        self.planes.append(GroundPlane(body_key, point, normal, colour))

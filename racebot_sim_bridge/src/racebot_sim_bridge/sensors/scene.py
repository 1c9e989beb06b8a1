"""What the cameras see of the world's colours: SceneColours.

A world built with visuals (physics.PhysicsWorld's default) has its colours already; one built
without draws each collision shape in a default grey, and SceneColours gives its SDF models the
colours their <visual><material> declares. Either way an SDF ground plane gets its colour, and
for the TinyRenderer it is drawn analytically (see SceneColours).
"""
import numpy as np
import pybullet as pb

from racebot_sim_bridge.engine.physics_types import BodyKind
from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.sensors.render import TINY, render


class GroundPlane:
    """An infinite plane the cameras draw themselves (see SceneColours)."""

    def __init__(self, body_key, point, normal, rgb):
        self.body_key = body_key
        self.point = np.asarray(point, dtype=np.float64)
        self.normal = np.asarray(normal, dtype=np.float64) / np.linalg.norm(normal)
        self.rgb = np.asarray(rgb, dtype=np.uint8)


class SceneColours:
    """Colours the bodies of SDF models as their visuals say (the first visual with a colour).

    Planes: a ground plane covers half of a camera's image, and rasterising it costs half of an
    800 x 800 frame in the TinyRenderer, and ~30 ms a frame in EGL on llvmpipe (its visual is a
    100 m box; PyBullet's OpenGL renderer does not draw a plane collision shape at all). Without a
    window, a world model's plane is therefore made invisible to the renderer and listed in
    `planes` with the colour the renderer gives it (measured once on a tiny image); cameras then
    draw it per pixel where it is nearer than what was rendered
    (camera.PinholeCamera.plane_inverse_depth), which gives the same picture for a fraction of the cost.
    With a window on this client the plane stays as it is (the window shows it).
    """

    def __init__(self, world, renderer=TINY):
        """`renderer`: the renderer the cameras use ('tiny' or 'egl'); plane colours are measured
        with it."""
        self.world = world
        self.renderer = renderer
        self.planes = []
        self.done = set()  # (model name, body id) of the bodies already coloured

    def refresh(self, models=()):
        """Colours every SDF body not coloured yet: those that carry their sdf_model.SdfModel
        (Model.source, as physics.PhysicsWorld records it) and those of `models`; forgets
        the planes of removed bodies."""
        world = self.world
        by_name = {m.name: m for m in models}
        for name, body in list(world.bodies.items()):
            key = (name, body.id)
            if key in self.done:
                continue
            model = body.source.model if body.source.kind is BodyKind.SDF else by_name.get(name)
            if model is not None:
                self.colour_model(model, body)
            self.done.add(key)
        alive = {(name, body.id) for name, body in world.bodies.items()}
        self.planes = [p for p in self.planes if p.body_key in alive]
        self.done &= alive

    def colour_model(self, model, body=None):
        """`model`: sdf_model.SdfModel, already added to the world (its Model found by name)."""
        body = body if body is not None else self.world.bodies.get(model.name)
        if body is None:
            return
        ids = {name: body.id for name, index in body.link_index.items() if index == -1}
        ids.update(dict(body.extra_bodies))
        for link in model.links:
            body_id = ids.get(link.name)
            if body_id is None:
                continue
            rgba = next((v.rgba for v in link.visuals if v.rgba), None)
            plane = next((c for c in link.collisions if c.shape.kind == 'plane'), None)
            # a world built with visuals has its colours already
            if plane is None and (rgba is None or getattr(self.world, "visuals", False)):
                continue
            kwargs = dict(rgbaColor=list(rgba or (0.8, 0.8, 0.8, 1.0)))
            if plane is not None:
                kwargs['textureUniqueId'] = -1  # PyBullet's checker texture is not the world's ground
            try:
                self.world.client.changeVisualShape(body_id, -1, **kwargs)
            except pb.error:
                continue  # a body without any drawable shape: nothing to colour
            if plane is not None and not self.world.gui:
                self._draw_analytically(model, link, plane, body_id, (model.name, body.id))

    def _draw_analytically(self, model, link, collision, body_id, body_key):
        position, orientation = model.world_pose_of(link, collision)
        normal = rotations.rotate(orientation, collision.shape.normal or (0.0, 0.0, 1.0))
        normal = np.asarray(normal) / np.linalg.norm(normal)
        point = np.asarray(position)
        # What the renderer draws for it: look at it from 1 cm away with a 1 degree field of view.
        eye = point + 0.01 * normal
        up = np.cross(normal, [1.0, 0.0, 0.0])
        if np.linalg.norm(up) < 1e-6:
            up = np.cross(normal, [0.0, 1.0, 0.0])
        client = self.world.client
        view = client.computeViewMatrix(eye.tolist(), point.tolist(), up.tolist())
        proj = client.computeProjectionMatrixFOV(1.0, 1.0, 0.001, 1.0)
        rgb, _ = render(self.world, 4, 4, view, proj, self.renderer)
        colour = rgb[2, 2].copy()
        client.changeVisualShape(body_id, -1, rgbaColor=[0.0, 0.0, 0.0, 0.0])
        self.planes.append(GroundPlane(body_key, point, normal, colour))

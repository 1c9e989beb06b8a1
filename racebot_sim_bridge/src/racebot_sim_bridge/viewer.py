"""Our gzclient: PyBullet's window showing a copy of the simulated world.

Physics always runs in a DIRECT client. Every call into a GUI client waits on its render thread,
so stepping the physics there makes a step cost a share of a frame (with software OpenGL the
simulation then crawls). Instead, this window holds its own copy of every body and receives poses
and joint positions about 30 times a second of wall time; the physics never waits on rendering.
"""
import pybullet as pb

from .physics import PhysicsWorld

SYNC_PERIOD = 1.0 / 30  # wall seconds between window updates


class Viewer(object):
    def __init__(self, world):
        """world: the simulated physics.PhysicsWorld. Raises physics.PhysicsError without a display."""
        self.world = world
        self.view = PhysicsWorld(world.step_size, world.gravity, gui=True)
        pb.configureDebugVisualizer(pb.COV_ENABLE_GUI, 0, physicsClientId=self.view.client)
        self.shown = {}  # body name -> (pose, joint positions) last sent to the window

    def sync(self):
        """Brings the window's bodies to the simulated state; call with the simulation's lock held."""
        world, view = self.world, self.view
        for name in [n for n in view.bodies if n not in world.bodies]:
            view.remove(name)
        for name, body in world.bodies.items():
            copy = view.bodies.get(name)
            if copy is None:
                copy = self._add(body)
                if copy is None:
                    continue
            if body.static:
                continue
            # Each call into the window waits for its render thread: send only what moved.
            pose = body.pose()
            joints = list(body.joints.values())
            positions = tuple(round(s.position, 4) for s in world.joint_states(body, [j.index for j in joints])) \
                if joints else ()
            last = self.shown.get(name)
            if last is not None and _close(last[0], pose) and last[1] == positions:
                continue
            self.shown[name] = (pose, positions)
            pb.resetBasePositionAndOrientation(copy.id, pose.position, pose.orientation, physicsClientId=view.client)
            if joints:
                pb.resetJointStatesMultiDof(copy.id, [copy.joints[j.name].index for j in joints],
                                            [[p] for p in positions], physicsClientId=view.client)
            if body.kind == 'urdf' and name == next(n for n, b in world.bodies.items() if b.kind == 'urdf'):
                view.follow_with_camera(copy)
        for name in [n for n in self.shown if n not in world.bodies]:
            del self.shown[name]

    def _add(self, body):
        source = getattr(body, 'source', None)
        if source is None:
            return None
        return self.view.add_copy(body.name, source)

    def close(self):
        self.view.close()


def _close(a, b, tol=1e-4):
    return all(abs(x - y) < tol for x, y in zip(a.position + a.orientation, b.position + b.orientation))

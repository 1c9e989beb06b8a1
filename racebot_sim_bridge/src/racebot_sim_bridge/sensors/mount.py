"""Where a sensor is: its pose (and motion) on a spawned body.

No rospy here. Calls run on the physics client; callers hold the simulator's lock.
- SensorMount: a sensor's pose on a spawned body. A sensor written on a link Gazebo lumps into its parent
  (a fixed joint) comes from the reader already moved to the link it was lumped into, its <pose> composed
  (description/sdf_reduction, as sdformat). A link kept by preserveFixedJoint is a PyBullet link of its own:
  the mount is that link. A link sdformat keeps but PyBullet merges (one fixed to a root named world) is
  mounted on the link it is merged into, at the fixed offset urdf_model computes.
"""
import numpy as np
import pybullet as pb

from racebot_sim_bridge.kinematics.rotations import compose


class SensorMount:
    def __init__(self, world, body, model, reference, sensor_pose=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)):
        """`body`: physics.Model of the robot; `model`: its urdf_model.RobotModel; `reference`: the sensor's
        link (SensorSpec.reference, after sdformat's lumping); `sensor_pose`: its <pose> (x y z r p y) in it.
        Raises KeyError when the link it is merged into is not a PyBullet link of the body."""
        self.world = world
        self.body = body
        self.link = model.lumped_link(reference)
        if self.link not in body.link_index:
            raise KeyError("link %r (carrying %r) is not a link of the spawned body (links: %s)"
                           % (self.link, reference, ', '.join(sorted(body.link_index))))
        self.index = body.link_index[self.link]
        self.offset = compose(model.pose_in_lumped_link(reference), sensor_pose)

    def _link(self, velocity):
        """(frame position, frame orientation, COM position, linear velocity at the COM, angular
        velocity) of the carrying link, all in world coordinates."""
        client, body = self.world.client, self.body
        if self.index < 0:
            com = body.pose()
            frame = body.frame_pose(com)  # from the same read of the base (was read twice)
            lin, ang = body.twist() if velocity else ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
            return frame.position, frame.orientation, com.position, lin, ang
        s = client.getLinkState(body.id, self.index, computeLinkVelocity=1 if velocity else 0,
                                computeForwardKinematics=1)
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

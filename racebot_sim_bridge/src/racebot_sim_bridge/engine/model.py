"""Model: one model in the world, as gazebo::physics::Model is one (its body, its links and joints by name, its
pose and velocity, the joints' array I/O, reset to where it was spawned, removal).

No ROS here. A Model is made by the world's loaders (physics.PhysicsWorld: urdf_spawn.py for a URDF robot,
sdf_bodies.py for an SDF model) and kept in `PhysicsWorld.bodies` by name. The array calls (joint_states_raw,
apply_efforts, drive_velocities, drive_positions) are what the update loop calls thousands of times a second:
each is one PyBullet call through the client's bound function, nothing between.
"""
from __future__ import annotations

from collections.abc import Iterable, Sequence

import pybullet as pb

from racebot_sim_bridge.engine import mimic_joints
from racebot_sim_bridge.engine.joint import Joint
from racebot_sim_bridge.engine.joint_damping import ImplicitDampers
from racebot_sim_bridge.engine.link import Link
from racebot_sim_bridge.engine.physics_types import BodySource, JointState, Pose, Twist
from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.kinematics.rotations import Quat, Vec3

TORQUE_CONTROL, VELOCITY_CONTROL, POSITION_CONTROL = pb.TORQUE_CONTROL, pb.VELOCITY_CONTROL, pb.POSITION_CONTROL


class Model:
    """A model in the world: its PyBullet body `id`, `links` ({name: Link}, link_index {name: PyBullet link
    index} of the body's own) and movable `joints` ({name: Joint}). `client`: the PybulletClient of the world it
    is in; `applied`: that world's accumulator of applied wrenches (see Link).

    `source`: the BodySource it was built from. `extra_bodies`: [(link name, PyBullet id)] of an SDF
    model's links after the first (each link its own body; the first is `id`, named `root_link`). `copy_key`:
    None until world_copy.body_key gives the model its identity across a delete and respawn under the same name.
    `model_offset`: for an SDF robot spawned as a URDF (sdf_urdf.py), its root link's pose in the SDF model
    frame, (xyz, quaternion), when not the identity; else None (a URDF's model frame is its root link's).
    `dampers`: the ImplicitDampers of its <implicitSpringDamper> joints (None without), which the world's step
    runs; `mimics`: its URDF <mimic> joints held to their leaders, {joint: mimic_joints.Coupling}."""

    def __init__(self, client: PybulletClient, applied: dict, name: str, body_id: int, static: bool,
                 source: BodySource, extra_bodies: Iterable[tuple[str, int]] = (),
                 root_link: str | None = None) -> None:
        self.client = client
        self.name = name
        self.id = body_id
        self.static = static
        self.source = source
        self.kind = source.kind
        self.extra_bodies = list(extra_bodies)
        self.copy_key = None
        self.one_sided_bodies = []  # its static bodies colliding through one-sided prisms (sdf_bodies.py)
        self.model_offset = None
        dyn = client.getDynamicsInfo(body_id, -1)
        self._inertial = (tuple(dyn[3]), tuple(dyn[4]))  # base inertial frame in the link frame
        self._inertial_inverse = pb.invertTransform(*self._inertial)  # frame_pose's, computed once
        self.spawn_pose = self.pose()
        self.initial_joint_positions = {}
        self.mimics = {}
        self.dampers = None
        self.wheel_friction = None  # its wheels' fdir1-aligned friction (wheel_friction.py), which the step runs
        self.damper_efforts = {}  # joint index -> effort applied for the coming step (with dampers only)
        self.link_index = {root_link or client.getBodyInfo(body_id)[0].decode(): -1}
        self.joints = {}
        for j in range(client.getNumJoints(body_id)):
            info = client.getJointInfo(body_id, j)
            self.link_index[info[12].decode()] = j
            if info[2] != pb.JOINT_FIXED:
                joint = Joint(self, info)
                self.joints[joint.name] = joint
        self.links = {link: Link(self, link, body_id, index, applied) for link, index in self.link_index.items()}
        for link, extra in self.extra_bodies:
            self.links[link] = Link(self, link, extra, -1, applied)

    def __repr__(self):
        return '<Model %s (%s, body %d)>' % (self.name, self.kind, self.id)

    # -- pose and velocity --------------------------------------------------------------------------
    def pose(self) -> Pose:
        """The base's centre-of-mass pose (what PyBullet's base calls take and give)."""
        pos, orn = self.client.getBasePositionAndOrientation(self.id)
        return Pose(tuple(pos), tuple(orn))

    def frame_pose(self, com: Pose | None = None) -> Pose:
        """The pose of the root link's frame, as Gazebo reports a model's pose; `com`: the base's pose() when
        already read (one PyBullet call fewer)."""
        pos, orn = self.pose() if com is None else com
        p, o = pb.multiplyTransforms(pos, orn, *self._inertial_inverse)
        return Pose(tuple(p), tuple(o))

    def com_pose_for_frame(self, position: Vec3, orientation: Quat) -> Pose:
        """The centre-of-mass pose that puts the root link's frame at (position, orientation)."""
        p, o = pb.multiplyTransforms(position, orientation, self._inertial[0], self._inertial[1])
        return Pose(tuple(p), tuple(o))

    def twist(self) -> Twist:
        """The base's world linear (at its centre of mass) and angular velocity."""
        lin, ang = self.client.getBaseVelocity(self.id)
        return Twist(tuple(lin), tuple(ang))

    def set_pose(self, position: Vec3, orientation: Quat, linear: Vec3 = (0, 0, 0),
                 angular: Vec3 = (0, 0, 0)) -> None:
        """Puts the base's centre of mass at (position, orientation) with a twist (its joints as they are)."""
        self.client.resetBasePositionAndOrientation(self.id, position, orientation)
        self.client.resetBaseVelocity(self.id, linear, angular)

    def set_velocity(self, linear: Vec3, angular: Vec3) -> None:
        """The base's world linear (at its centre of mass) and angular velocity, its pose left as it is."""
        self.client.resetBaseVelocity(self.id, list(linear), list(angular))

    def link_names(self) -> list[str]:
        return list(self.link_index)

    # -- joints, many at once (the update loop's) ----------------------------------------------------
    def joint_states(self, indices: Sequence[int]) -> list[JointState]:
        """JointState of each joint of `indices` (PyBullet joint indices, Joint.index)."""
        return [JointState(s[0], s[1]) for s in self.client.getJointStates(self.id, indices)]

    def joint_states_raw(self, indices: Sequence[int]) -> list[tuple[float, float, tuple[float, ...], float]]:
        """PyBullet's own tuples (position, velocity, reaction forces, applied torque) of the joints:
        the update loop's read, without building a JointState per joint."""
        return self.client.getJointStates(self.id, indices)

    def apply_efforts(self, indices: Sequence[int], efforts: Sequence[float]) -> None:
        """Torques (or forces) for one step: PyBullet clears them after every stepSimulation."""
        self.client.setJointMotorControlArray(self.id, indices, TORQUE_CONTROL, forces=efforts)
        if self.dampers is not None:
            applied = self.damper_efforts
            for index, effort in zip(indices, efforts):
                applied[index] = applied.get(index, 0.0) + effort

    def drive_velocities(self, indices: Sequence[int], velocities: Sequence[float],
                         max_forces: Sequence[float]) -> None:
        """PyBullet's velocity motors of the joints towards `velocities`, each with at most its max force."""
        self.client.setJointMotorControlArray(self.id, indices, VELOCITY_CONTROL, targetVelocities=velocities,
                                              forces=max_forces)

    def drive_positions(self, indices: Sequence[int], positions: Sequence[float],
                        max_forces: Sequence[float]) -> None:
        """PyBullet's position motors of the joints towards `positions`, each with at most its max force."""
        self.client.setJointMotorControlArray(self.id, indices, POSITION_CONTROL, targetPositions=positions,
                                              forces=max_forces)

    def set_dampers(self, dampers: ImplicitDampers) -> None:
        """Gives the model its implicitly damped joints (joint_damping.py), run by damp() before each step."""
        self.dampers = dampers

    def damp(self, step_size: float) -> None:
        """The implicit dampers' torques for the coming step of `step_size`, from the efforts applied so far."""
        indices, torques = self.dampers.torques(step_size, self.damper_efforts)
        if indices:
            self.client.setJointMotorControlArray(self.id, indices, TORQUE_CONTROL, forces=torques)
        if self.damper_efforts:
            self.damper_efforts = {}

    # -- reset and removal ----------------------------------------------------------------------------
    def reset(self) -> None:
        """Back to where it was spawned (Model::Reset): pose, velocities, joints at their initial positions."""
        pos, orn = self.spawn_pose
        self.set_pose(pos, orn)
        for link, extra in self.extra_bodies:  # an SDF model's other links, as spawned
            pos, orn = self.source.model.world_pose_of(link)
            self.links[link].set_base_state(pos, orn)
        for joint in self.joints.values():
            self.client.resetJointState(self.id, joint.index, self.initial_joint_positions.get(joint.name, 0.0), 0.0)
        mimic_joints.settle(self.client, self.id, self.joints, self.mimics)
        if self.wheel_friction is not None:
            self.wheel_friction.reset()

    def body_ids(self) -> list[int]:
        """Its PyBullet bodies: its own and an SDF model's other links'."""
        return [self.id] + [extra for _, extra in self.extra_bodies]

    def remove(self) -> None:
        """Takes its PyBullet bodies out of the client (PhysicsWorld.remove forgets it too)."""
        for body_id in self.body_ids():
            self.client.removeBody(body_id)

"""The world's models and links as gazebo_ros's state services see them: found by name, posed, moved.

No rospy. Callers hold `Simulator.lock`. A model's pose is its model frame (Gazebo's Model::WorldPose):
a URDF model's root link frame (of an SDF robot spawned as a URDF, less the root link's pose in the SDF
model, Model.model_offset); an SDF model's <pose> (its first link's body, less that link's pose in the
model). Links: a URDF model's links after the fixed-joint merge (what Gazebo keeps as links); an SDF
model's links, each its own PyBullet body. Twists are PyBullet's (centre-of-mass velocities).

PyBullet holds an articulated model in reduced coordinates, so one link cannot be put somewhere on its
own: set_link_state on a URDF link moves its whole model rigidly (joint positions kept, joint velocities
zeroed) so that the link lands on the pose asked. set_model_state zeroes joint velocities too, as
Gazebo's Model::SetLinearVel / SetAngularVel give every link the same velocity.
"""
from racebot_sim_bridge.gazebo_ros_api import frames
from racebot_sim_bridge.engine.physics_types import BodyKind, Pose
from racebot_sim_bridge.kinematics.rotations import as_transform, inverse


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


class WorldEntities:
    def __init__(self, world):
        """world: physics.PhysicsWorld."""
        self.world = world

    # -- names ----------------------------------------------------------------------------------
    def entries(self):
        """frames.ModelEntry of every model, in the world's order (world file first, then spawned)."""
        return [frames.ModelEntry(name, self.link_names(body), list(body.joints))
                for name, body in self.world.bodies.items()]

    def resolve(self, name):
        return frames.resolve(name, self.entries())

    def find_link(self, name):
        """The Entity of a link called `name` (scoped or not); None for models, joints and unknowns."""
        entity = self.resolve(name)
        return entity if entity is not None and entity.link is not None else None

    def model_body(self, name):
        """The physics Model called `name` (World::ModelByName: a link's name is no model); None if none."""
        entity = self.resolve(name)
        return self.world.bodies[entity.model] if entity is not None and entity.link is None else None

    def find_joint(self, name):
        """(Model, joint name) of the joint called `name` as Model::GetJoint finds it, model by model: its plain or
        scoped name; (None, None) when no model has it."""
        for model, body in self.world.bodies.items():
            for joint in body.joints:
                if name in (joint, '%s::%s' % (model, joint)):
                    return body, joint
        return None, None

    @staticmethod
    def link_names(body):
        return list(body.link_index) + [link for link, _ in body.extra_bodies]

    # -- state ------------------------------------------------------------------------------------
    def state(self, entity):
        """(Pose, Twist) in the world of an Entity (model or link)."""
        body = self.world.bodies[entity.model]
        if entity.link is None:
            return self.model_state(body)
        return self.link_state(body, entity.link)

    def frame_state(self, name):
        """(Pose, Twist) in the world of the entity (model or link) called `name`, as a reference frame: (None, None)
        for the world's names, (False, None) when nothing has that name."""
        entity = self.resolve(name)
        if entity is not None:
            return self.state(entity)
        return (None, None) if frames.is_world_frame(name) else (False, None)

    def model_state(self, body):
        pose, twist = body.frame_pose(), body.twist()
        offset = self._root_link_in_model(body)
        if offset is not None:
            pose = Pose(*frames.in_world(pose, inverse(offset)))
        return pose, twist

    def link_state(self, body, link):
        return body.links[link].state()

    # -- moves ------------------------------------------------------------------------------------
    def set_model_state(self, body, pose, twist):
        """Puts the model frame at `pose` (world) and gives every link `twist`."""
        offset = self._root_link_in_model(body)
        if body.kind is not BodyKind.SDF:
            self._place_articulated(body, pose if offset is None else frames.in_world(pose, offset), twist)
            return
        old = self.model_state(body)[0]
        root = frames.in_world(pose, offset)
        body.set_pose(root[0], root[1], twist[0], twist[1])
        for name, _ in body.extra_bodies:
            link = body.links[name]
            moved = frames.in_world(pose, frames.relative_to(old, link.state()[0]))
            link.set_base_state(moved[0], moved[1], twist[0], twist[1])

    def set_link_state(self, body, link, pose, twist):
        """Puts link `link` at `pose` (world) with `twist`; see the module's note for URDF links."""
        if link in dict(body.extra_bodies):
            body.links[link].set_base_state(pose[0], pose[1], twist[0], twist[1])
            return
        link_pose = body.links[link].state()[0]
        root = body.frame_pose()
        new_root = frames.in_world(pose, frames.relative_to(link_pose, root))
        # the base's velocity that gives the link `twist` when the model moves as one rigid body
        # (taken at the link's frame origin, which is close to its centre of mass)
        arm = tuple(b - a for a, b in zip(pose[0], body.com_pose_for_frame(*new_root).position))
        linear = tuple(v + w for v, w in zip(twist[0], _cross(twist[1], arm)))
        if body.kind is not BodyKind.SDF:
            self._place_articulated(body, new_root, (linear, twist[1]))
        else:  # an SDF model's first link: its body alone
            body.set_pose(new_root[0], new_root[1], linear, twist[1])

    def _place_articulated(self, body, frame_pose, twist):
        com = body.com_pose_for_frame(*frame_pose)
        body.set_pose(com.position, com.orientation, twist[0], twist[1])
        if body.joints:
            joints = list(body.joints.values())
            states = body.joint_states([j.index for j in joints])
            for joint, s in zip(joints, states):
                joint.set_position(s.position, 0.0)

    @staticmethod
    def _root_link_in_model(body):
        """The root link's (an SDF model's first link's) pose in the model frame; None for the identity."""
        if body.kind is not BodyKind.SDF:
            return body.model_offset
        first = next(iter(body.link_index))
        return as_transform(body.source.model.link(first).pose)


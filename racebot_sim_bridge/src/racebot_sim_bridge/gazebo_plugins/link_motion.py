"""A link's world pose and motion as Gazebo's Link reports them: WorldPose is the link's frame and
WorldLinearVel the velocity of the frame's origin, while PyBullet gives the centre of mass's. No rospy."""
from racebot_sim_bridge.kinematics.rotations import conjugate, quaternion_multiply, rotate_back


def point_velocity(com_velocity, angular, com, point):
    """Velocity of a point of a rigid body: v_com + w x (point - com)."""
    rx, ry, rz = (point[i] - com[i] for i in range(3))
    wx, wy, wz = angular
    return (com_velocity[0] + wy * rz - wz * ry,
            com_velocity[1] + wz * rx - wx * rz,
            com_velocity[2] + wx * ry - wy * rx)


def link_motion(world, body, link):
    """(position, quaternion xyzw, linear velocity of the frame origin, angular velocity), all in world
    axes, of the PyBullet link `link` (a name in body.link_index; the root link is the base)."""
    index = body.link_index[link]
    if index < 0:  # the base: PyBullet's base calls read directly (an IMU asks 50-100 times a sim second)
        client = world.client
        com_position, com_orientation = client.getBasePositionAndOrientation(body.id)
        position, orientation = body.frame_pose((com_position, com_orientation))
        linear, angular = client.getBaseVelocity(body.id)
    else:
        s = world.client.getLinkState(body.id, index, computeLinkVelocity=1, computeForwardKinematics=1)
        com_position, position, orientation, linear, angular = s[0], s[4], s[5], s[6], s[7]
    return (tuple(position), tuple(orientation), point_velocity(linear, angular, com_position, position),
            tuple(angular))


def model_relative_pose(world, body, root, link):
    """(position, quaternion xyzw) of link `link`'s frame in the model's frame (the frame of its root link
    `root`): Gazebo's Link::RelativePose, what the drive plugins' wheel TFs send."""
    model_position, model_orientation, _, _ = link_motion(world, body, root)
    position, orientation, _, _ = link_motion(world, body, link)
    relative = rotate_back(model_orientation, tuple(position[i] - model_position[i] for i in range(3)))
    return relative, quaternion_multiply(conjugate(model_orientation), orientation)

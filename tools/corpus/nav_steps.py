"""The ROS steps of the corpus's `navigation` check (checks.check_navigation): the initial pose a user gives amcl,
a scripted route with the ground truth sampled meanwhile, one move_base goal, a pose read off TF."""
import math
import time

import rospy

from corpus.ros_io import WALL_MARGIN_S, CheckFailed, Commander, model_pose, sim_sleep, yaw_of


def initial_pose(check, truth, frame):
    """Numbers of the initial pose. `publish`: what the tutorial's user does with rviz's 2D Pose Estimate, a
    PoseWithCovarianceStamped on /initialpose with rviz's covariance, here at the ground truth `truth` (map frame).
    `launch_default`: amcl's own ~initial_pose_* parameters, which must then be the ground truth (amcl saves its
    estimate there every 2 s, save_pose_rate: before any motion, the launch default's neighbourhood)."""
    from geometry_msgs.msg import PoseWithCovarianceStamped
    from corpus import navigation
    amcl = check.get('amcl', '/amcl')
    default = tuple(float(rospy.get_param('%s/initial_pose_%s' % (amcl, k), 0.0)) for k in 'xya')
    off = math.hypot(default[0] - truth[0], default[1] - truth[1])
    said = "amcl's %s/initial_pose_* (%.2f, %.2f, %.2f) %.3f m from the ground truth in the map (%.3f, %.3f, %.3f)" % (
        amcl, default[0], default[1], default[2], off, truth[0], truth[1], truth[2])
    if check['initial_pose'] == 'launch_default':
        if off > float(check['localisation_tolerance']):
            raise CheckFailed("the row says amcl's launch default is the robot's pose: " + said)
        return said + ': no 2D Pose Estimate'
    pub = rospy.Publisher('/initialpose', PoseWithCovarianceStamped, queue_size=1, latch=True)
    deadline = time.time() + 30.0
    while pub.get_num_connections() == 0:
        if time.time() > deadline:
            raise CheckFailed('nothing subscribes to /initialpose in 30 s (amcl is not up)', said)
        time.sleep(0.2)
    msg = PoseWithCovarianceStamped()
    msg.header.frame_id, msg.header.stamp = frame, rospy.get_rostime()
    msg.pose.pose.position.x, msg.pose.pose.position.y = truth[0], truth[1]
    msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = math.sin(truth[2] / 2), math.cos(truth[2] / 2)
    msg.pose.covariance = [navigation.RVIZ_COVARIANCE.get(i, 0.0) for i in range(36)]
    pub.publish(msg)
    return said + '; 2D Pose Estimate on /initialpose at the ground truth'


def drive_sampled(check, getter, model, to_map):
    """Drives `route` ([vx, wz, sim s] on `cmd_topic`), then stands still `settle` s; the ground truth in the map
    frame meanwhile, [(x, y, yaw, stamp)] every 0.1 s of sim time."""
    from corpus import map_registration
    cmd = Commander(dict(check, vx=0.0, wz=0.0))
    history = []
    try:
        for vx, wz, seconds in list(check['route']) + [[0.0, 0.0, float(check.get('settle', 2.0))]]:
            cmd.msg.linear.x, cmd.msg.angular.z = float(vx), float(wz)
            end = rospy.get_rostime().to_sec() + float(seconds)
            while rospy.get_rostime().to_sec() < end:
                x, y, yaw, stamp = model_pose(getter, model)
                history.append(map_registration.compose(to_map, (x, y, yaw)) + (stamp,))
                sim_sleep(0.1)
    finally:
        cmd.stop()
    return history


def reach(client, goal, frame, timeout):
    """Sends one move_base goal (x, y, yaw in `frame`); (its final state's name, sim seconds it took, status text),
    cancelled after `timeout` sim s."""
    from actionlib_msgs.msg import GoalStatus
    from move_base_msgs.msg import MoveBaseGoal
    msg = MoveBaseGoal()
    msg.target_pose.header.frame_id, msg.target_pose.header.stamp = frame, rospy.get_rostime()
    pose = msg.target_pose.pose
    pose.position.x, pose.position.y = goal[0], goal[1]
    pose.orientation.z, pose.orientation.w = math.sin(goal[2] / 2), math.cos(goal[2] / 2)
    start = rospy.get_rostime().to_sec()
    client.send_goal(msg)
    deadline = time.time() + timeout * 4 + WALL_MARGIN_S
    while client.get_state() in (GoalStatus.PENDING, GoalStatus.ACTIVE):
        elapsed = rospy.get_rostime().to_sec() - start
        if elapsed > timeout or time.time() > deadline or rospy.is_shutdown():
            client.cancel_goal()
            return 'not done', elapsed, 'cancelled: %s' % (
                'no result in %.0f s of sim time' % timeout if elapsed > timeout else
                'sim time stalled, %.1f s of it in %.0f s' % (elapsed, timeout * 4 + WALL_MARGIN_S))
        time.sleep(0.1)
    names = {v: k for k, v in vars(GoalStatus).items() if k.isupper() and isinstance(v, int)}
    state = client.get_state()
    return names.get(state, str(state)), rospy.get_rostime().to_sec() - start, client.get_goal_status_text()


def tf_pose(buffer, frame, base):
    import tf2_ros
    try:
        t = buffer.lookup_transform(frame, base, rospy.Time(0), rospy.Duration(10.0)).transform
    except tf2_ros.TransformException as err:
        raise CheckFailed('no transform %s -> %s: %s' % (frame, base, err))
    return t.translation.x, t.translation.y, yaw_of(t.rotation)

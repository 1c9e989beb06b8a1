#!/usr/bin/env python3
"""The checks of one corpus row, against a simulation the row's commands started (run.py runs this
in a child process with the row's environment: its workspace sourced, its ROS master).

    checks.py ROW_JSON RESULT_JSON

Every check is a black box on the ROS interfaces a Gazebo user has: topics, the /gazebo services,
controller_manager and actionlib. Waits are bounded in wall time, so a world whose /clock stops ends a
check with a reason instead of hanging.
"""
import json
import math
import os
import subprocess
import sys
import time
import traceback
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import rospy  # noqa: E402

from corpus import floor, sensors  # noqa: E402
from corpus.drive_path import travelled  # noqa: E402
from corpus.flight_check import check_flight  # noqa: E402
from corpus.topics_agree import check_topics_agree  # noqa: E402
from corpus.ros_io import (MESSAGE_TIMEOUT_S, WALL_MARGIN_S, CheckFailed, Commander, Latest, message,  # noqa: E402
                           model_pose, service, sim_sleep, yaw_of)

PATH_TOLERANCE_VIOLATED = -4  # control_msgs/FollowJointTrajectoryResult
DRIVE_SAMPLE_S = 0.1  # s of sim time between the poses a drive check's path is summed from


def joint_positions(topic):
    msg = message(topic, 'sensor_msgs/JointState')
    return dict(zip(msg.name, msg.position))


def wait_ready(row):
    """Until the world answers and the row's model is in it (or the row has none)."""
    from gazebo_msgs.srv import GetWorldProperties
    timeout = float(row.get('ready_timeout', 120))
    props = service('/gazebo/get_world_properties', GetWorldProperties, timeout)
    deadline = time.time() + timeout
    model = row.get('model')
    names = []
    while time.time() < deadline:
        try:
            names = props().model_names
        except rospy.ServiceException:
            names = []
        if not model or model in names:
            if rospy.get_rostime().to_sec() > 0:
                return
        time.sleep(1.0)
    if model in names:
        raise CheckFailed('%r is in the world but sim time is 0 after %.0f s: the world stayed paused' % (
            model, timeout))
    raise CheckFailed('model %r not in the world after %.0f s (world has: %s)' % (model, timeout, ', '.join(names)))


# --- the kinds --------------------------------------------------------------------------------------

def check_controllers(check, row):
    from controller_manager_msgs.srv import ListControllers
    lister = service(check['manager'] + '/list_controllers', ListControllers, 60.0)
    want = list(check['running'])
    deadline = time.time() + float(check.get('timeout', 60))
    states = {}
    while time.time() < deadline:
        try:
            states = {c.name: c.state for c in lister().controller}
        except rospy.ServiceException:
            states = {}
        if all(states.get(n) == 'running' for n in want):
            break
        time.sleep(1.0)
    running = [n for n in want if states.get(n) == 'running']
    numbers = '%d/%d running' % (len(running), len(want))
    bad = ['%s: %s' % (n, states.get(n, 'not loaded')) for n in want if n not in running]
    if bad:
        raise CheckFailed(numbers + '; ' + ', '.join(bad))
    return numbers + ' (%s)' % ', '.join(want)


def check_drive(check, row):
    """Drives with a constant command; judges the ground-truth speed (and yaw rate) against what the
    robot's own parameters say it must be, and the odometry's distance against the ground truth's."""
    from gazebo_msgs.srv import GetModelState
    getter = service('/gazebo/get_model_state', GetModelState)
    model = check.get('model', row.get('model'))
    odom = Latest(check['odom_topic'], 'nav_msgs/Odometry') if check.get('odom_topic') else None
    cmd = Commander(check)
    seconds = float(check['seconds'])
    samples = max(1, int(round(seconds / DRIVE_SAMPLE_S)))
    try:
        sim_sleep(float(check.get('settle', 2.0)))
        x0, y0, th0, t0 = model_pose(getter, model)
        o0 = odom.msg if odom else None
        poses = [(x0, y0, th0)]
        for _ in range(samples):  # the path, not the chord: a turning drive's arc is longer (drive_path.py)
            sim_sleep(seconds / samples)
            x1, y1, th1, t1 = model_pose(getter, model)
            poses.append((x1, y1, th1))
        o1 = odom.msg if odom else None
    finally:
        cmd.stop()
    dt = t1 - t0
    if dt <= 0:
        raise CheckFailed('sim time did not advance between the two model states')
    dist, turned = travelled(poses)
    speed, yaw_rate = dist / dt, turned / dt
    chord = math.hypot(x1 - x0, y1 - y0)  # what the odometry's first and last poses are compared with
    tol = float(check['tolerance'])
    want = float(check['expect_speed'])
    numbers = 'ground truth %.3f m/s over %.1f s (expected %.3f +-%.0f%%)' % (speed, dt, want, tol * 100)
    problems = []
    if abs(speed - want) > tol * max(abs(want), 0.05):
        problems.append('speed %.3f m/s, expected %.3f' % (speed, want))
    if 'expect_yaw_rate' in check:
        want_w = float(check['expect_yaw_rate'])
        numbers += '; yaw rate %.3f rad/s (expected %.3f)' % (yaw_rate, want_w)
        if abs(yaw_rate - want_w) > tol * max(abs(want_w), 0.05):
            problems.append('yaw rate %.3f rad/s, expected %.3f' % (yaw_rate, want_w))
    if odom:
        if o0 is None or o1 is None:
            problems.append('no odometry on %s' % check['odom_topic'])
        else:
            p0, p1 = o0.pose.pose.position, o1.pose.pose.position
            odist = math.hypot(p1.x - p0.x, p1.y - p0.y)
            numbers += '; odometry %s %.3f m vs ground truth %.3f m' % (check['odom_topic'], odist, chord)
            if abs(odist - chord) > tol * max(chord, 0.05):
                problems.append('odometry says %.3f m, ground truth %.3f m' % (odist, chord))
    if problems:
        raise CheckFailed('; '.join(problems), numbers)
    return numbers


def check_joint_position(check, row):
    from std_msgs.msg import Float64
    pub = rospy.Publisher(check['command_topic'], Float64, queue_size=1, latch=True)
    target, tol, joint = float(check['target']), float(check['tolerance']), check['joint']
    time.sleep(1.0)
    pub.publish(Float64(target))
    sim_sleep(float(check.get('seconds', 5.0)))
    got = joint_positions(check['joint_states']).get(joint)
    if got is None:
        raise CheckFailed('%s not in %s' % (joint, check['joint_states']))
    numbers = '%s at %.4f rad, target %.4f +-%.3f' % (joint, got, target, tol)
    if abs(got - target) > tol:
        raise CheckFailed(numbers)
    return numbers


def _goal_tolerance(check, joint):
    """The controller's own goal tolerance for `joint` (its constraints/<joint>/goal), else the row's."""
    param = check.get('tolerance_param')
    if param:
        value = rospy.get_param(param.format(joint=joint), 0.0)
        if value and value > 0:
            return float(value), param.format(joint=joint)
    return float(check['tolerance']), 'row'


def controller_hold(controller):
    """(largest |desired - actual| of the trajectory controller under `controller`, its joint) as its `state`
    topic reads now: how far from the joints the position it holds is. (0.0, '-') for a controller without that
    topic (robot_controllers' FollowJointTrajectoryController has only its action), which has no start race either."""
    topics = [name for name, _ in rospy.get_published_topics()]
    if controller + '/state' not in topics:
        return 0.0, '-'
    state = message(controller + '/state', 'control_msgs/JointTrajectoryControllerState')
    return max(zip((abs(e) for e in state.error.positions), state.joint_names), default=(0.0, '-'))


def _path_tolerance(controller, joint):
    value = rospy.get_param('%s/constraints/%s/trajectory' % (controller, joint), 0.0)
    return float(value) if value and value > 0 else None


def start_race(code, held, path_tolerance):
    """True when an abort is upstream's start race (universal_robot#627): a PATH_TOLERANCE_VIOLATED goal sent while
    the controller held, before the goal, further from the joints than its own path tolerance (the `held` joint's
    constraints/<joint>/trajectory; None when it has none, and then nothing is a start race). Started while an
    effort-driven arm still fell, joint_trajectory_controller holds where stop_trajectory_duration carries the fall
    on (below the ground), and a goal's first segment starts from that hold, in Gazebo as here."""
    return code == PATH_TOLERANCE_VIOLATED and path_tolerance is not None and held[0] > path_tolerance


def _send_goal(client, target, duration):
    from control_msgs.msg import FollowJointTrajectoryGoal
    from trajectory_msgs.msg import JointTrajectoryPoint
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = list(target)
    goal.trajectory.points = [JointTrajectoryPoint(positions=list(target.values()),
                                                   time_from_start=rospy.Duration(duration))]
    client.send_goal(goal)
    if not client.wait_for_result(rospy.Duration(duration + WALL_MARGIN_S)):
        raise CheckFailed('no result in %.0f s' % (duration + WALL_MARGIN_S))
    result = client.get_result()
    return (result.error_code if result is not None else None), (result.error_string if result else 'no result')


def check_trajectory(check, row):
    """What a user does: once the controllers run (the controllers check before this one), wait settle_s (the
    moment it takes to type the goal), send a FollowJointTrajectory goal, read the result and where the joints
    end. When that first goal is aborted by upstream's start race (start_race), the user sends it again, as
    universal_robot#627's users do ("the arm can be controlled just fine") once the arm has stopped moving along
    the aborted goal's trajectory; the numbers say so."""
    import actionlib
    from control_msgs.msg import FollowJointTrajectoryAction
    controller = check['action'].rsplit('/', 1)[0]
    client = actionlib.SimpleActionClient(check['action'], FollowJointTrajectoryAction)
    if not client.wait_for_server(rospy.Duration(60.0)):
        raise CheckFailed('action server %s not up in 60 s' % check['action'])
    if check.get('settle_s'):
        sim_sleep(float(check['settle_s']))
    now = joint_positions(check['joint_states'])
    target = {j: float(v) + (now.get(j, 0.0) if check.get('relative') else 0.0) for j, v in check['target'].items()}
    duration = float(check['duration'])
    held = controller_hold(controller)
    code, why = _send_goal(client, target, duration)
    first = None
    if start_race(code, held, _path_tolerance(controller, held[1])):
        first = ('first goal aborted (%s: %s): the controller held %.3f rad (%s) from the joints before it, '
                 "upstream's start race (universal_robot#627); sent again once its trajectory's time had passed"
                 % (code, why, held[0], held[1]))
        sim_sleep(duration)  # upstream's controller goes on along an aborted goal's trajectory: the user sees it end
        code, why = _send_goal(client, target, duration)
    sim_sleep(0.5)
    final = joint_positions(check['joint_states'])
    worst, worst_joint, bad = 0.0, None, []
    for joint, want in target.items():
        err = abs(final.get(joint, float('nan')) - want)
        tol, source = _goal_tolerance(check, joint)
        if not err <= tol:
            bad.append('%s %.4f rad off (tolerance %.3f from %s)' % (joint, err, tol, source))
        if not err <= worst:
            worst, worst_joint = err, joint
    numbers = 'error_code %s, max |error| %.4f rad (%s), %d joints' % (code, worst, worst_joint, len(target))
    if first:
        numbers += '; ' + first
    if code != 0:  # where the goal started from: a failure is read against the robot's pose then
        start = ', '.join('%s %.3f' % (j, now[j]) for j in target if j in now)
        raise CheckFailed('error_code %s (%s); %s; started from %s, the controller holding %.3f rad (%s) from the '
                          'joints' % (code, why, numbers, start, held[0], held[1]))
    if bad:
        raise CheckFailed('; '.join(bad), numbers)
    return numbers


def check_gripper(check, row):
    import actionlib
    from actionlib_msgs.msg import GoalStatus
    from control_msgs.msg import GripperCommandAction, GripperCommandGoal
    client = actionlib.SimpleActionClient(check['action'], GripperCommandAction)
    if not client.wait_for_server(rospy.Duration(60.0)):
        raise CheckFailed('action server %s not up in 60 s' % check['action'])
    goal = GripperCommandGoal()
    goal.command.position, goal.command.max_effort = float(check['position']), float(check.get('max_effort', 0.0))
    client.send_goal(goal)
    if not client.wait_for_result(rospy.Duration(float(check.get('seconds', 10)) + WALL_MARGIN_S)):
        raise CheckFailed('no result')
    state, result = client.get_state(), client.get_result()
    got = joint_positions(check['joint_states']).get(check['joint'])
    tol, want = float(check['tolerance']), float(check.get('joint_target', check['position']))
    numbers = '%s at %s (expected %.4f +-%.4f), action %s, reached_goal %s' % (
        check['joint'], '%.4f' % got if got is not None else 'absent', want, tol,
        GoalStatus.to_string(state) if hasattr(GoalStatus, 'to_string') else state,
        getattr(result, 'reached_goal', None))
    if got is None or abs(got - want) > tol or state != GoalStatus.SUCCEEDED:
        raise CheckFailed(numbers)
    return numbers


def observe(msg):
    """The attributes sensors.compare judges, read off one message."""
    seen = {}
    for key in ('width', 'height', 'encoding', 'angle_min', 'angle_max', 'range_max'):
        if hasattr(msg, key):
            seen[key] = getattr(msg, key)
    if hasattr(msg, 'ranges'):
        seen['len(ranges)'] = len(msg.ranges)
    if hasattr(msg, 'orientation'):
        q = msg.orientation
        values = (q.x, q.y, q.z, q.w)
        seen['finite(orientation)'] = all(math.isfinite(v) for v in values) and abs(
            math.sqrt(sum(v * v for v in values)) - 1.0) < 1e-2
    if hasattr(msg, 'fields') and any(f.name == 'ring' for f in msg.fields):
        from sensor_msgs import point_cloud2
        rings = [p[0] for p in point_cloud2.read_points(msg, field_names=('ring',))]
        seen['ring_max'] = max(rings) if rings else None
    return seen


def check_sensors(check, row):
    xml = rospy.get_param(check['description'], None)
    if not xml:
        raise CheckFailed('no robot description on %s' % check['description'])
    expects, unchecked = sensors.declared(xml, check.get('namespace', ''))
    lines, bad = [], []
    if len(expects) != int(check['count']):
        bad.append('the description declares %d sensor topics, the row expects %d' % (len(expects), check['count']))
    for e in expects:
        try:
            seen = observe(message(e['topic'], e['type']))
            mismatch = sensors.compare(e['fields'], seen)
        except CheckFailed as err:
            mismatch, seen = str(err), {}
        shown = ', '.join('%s=%s' % (k, round(v, 4) if isinstance(v, float) else v) for k, v in sorted(seen.items()))
        if mismatch:
            bad.append('%s (%s): %s' % (e['topic'], e['plugin'], mismatch))
            lines.append('%s FAIL' % e['topic'])
        else:
            lines.append('%s ok (%s)' % (e['topic'], shown))
    numbers = '%d/%d topics right: %s' % (len(expects) - sum(1 for x in lines if x.endswith('FAIL')), len(expects),
                                          '; '.join(lines))
    if unchecked:
        numbers += '; not checked (no rule): ' + '; '.join(unchecked)
    if bad:
        raise CheckFailed('; '.join(bad), numbers)
    return numbers


def exported_paths(attribute, variable):
    """A Gazebo path as gazebo_ros would set it: the variable's folders, then every package's export of
    `attribute` (rospack plugins)."""
    paths = [p for p in os.environ.get(variable, '').split(':') if p]
    done = subprocess.run(['rospack', 'plugins', '--attrib=' + attribute, 'gazebo_ros'],
                          stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    return paths + [line.split(' ', 1)[1] for line in done.stdout.splitlines() if ' ' in line]


def model_paths():
    """Gazebo's model path as gazebo_ros would set it: GAZEBO_MODEL_PATH, every package's
    gazebo_model_path export, ~/.gazebo/models."""
    return exported_paths('gazebo_model_path', 'GAZEBO_MODEL_PATH') + [os.path.expanduser('~/.gazebo/models')]


def included_name(uri, paths):
    """The name Gazebo gives an <include> without <name>: the included model's own, or None for a light."""
    model = uri.replace('model://', '').strip('/')
    for root in paths:
        config = os.path.join(root, model, 'model.config')
        if os.path.isfile(config):
            sdf = ET.parse(config).getroot().findtext('sdf', 'model.sdf').strip()
            tree = ET.parse(os.path.join(root, model, sdf)).getroot()
            found = tree.find('model')
            if found is None:
                return None if tree.find('light') is not None else model
            return found.get('name')
    return None if model == 'sun' else model.split('/')[-1]


def world_models(path):
    """The models a world file declares at its top level: <model name> and <include>s (lights left out)."""
    with open(path, 'rb') as f:
        root = ET.fromstring(f.read().strip())
    world = root.find('world')
    names, paths = [], None
    for child in world:
        if child.tag == 'model':
            names.append(child.get('name'))
        elif child.tag == 'include':
            name = child.findtext('name')
            if name is None:
                paths = paths if paths is not None else model_paths()
                name = included_name(child.findtext('uri', ''), paths)
            if name:
                names.append(name.strip())
    return names


def resolve_find(text):
    import rospkg
    if text.startswith('$(find '):
        package, rest = text[len('$(find '):].split(')', 1)
        return rospkg.RosPack().get_path(package) + rest
    return text


def check_world(check, row):
    from gazebo_msgs.msg import LinkStates
    from gazebo_msgs.srv import GetWorldProperties
    path = resolve_find(check['world'])
    declared = world_models(path)
    if len(declared) < int(check['min_models']):
        raise CheckFailed('the world file declares %d models, the row expects at least %d' % (
            len(declared), check['min_models']))
    present = set(service('/gazebo/get_world_properties', GetWorldProperties)().model_names)
    links = rospy.wait_for_message('/gazebo/link_states', LinkStates, timeout=MESSAGE_TIMEOUT_S).name
    with_links = {name.split('::', 1)[0] for name in links}
    missing = [m for m in declared if m not in present]
    linkless = [m for m in declared if m in present and m not in with_links]
    listed = len(declared) - len(missing)
    numbers = '%d/%d models of %s listed by get_world_properties, %d with links in link_states' % (
        listed, len(declared), os.path.basename(path), listed - len(linkless))
    problems = []
    if missing:
        problems.append('missing: ' + ', '.join(missing[:8]) + ('...' if len(missing) > 8 else ''))
    if linkless:
        problems.append('no links: ' + ', '.join(linkless[:8]) + ('...' if len(linkless) > 8 else ''))
    if problems:
        raise CheckFailed('%d/%d models loaded; %s' % (listed, len(declared), '; '.join(problems)), numbers)
    return numbers


def check_plugin_output(check, row):
    """A compiled plugin's own words: `text` in the commands' output (the world server's screen, where roslaunch
    shows it) at least `count` times, within `timeout` s (default 30) of the row being ready."""
    text, count = check['text'], int(check['count'])
    timeout = float(check.get('timeout', 30))
    folder = row['logs_dir']
    deadline = time.time() + timeout
    found = {}
    while True:
        found = {}
        for name in sorted(os.listdir(folder)):
            if name.startswith('command-') and name.endswith('.log'):
                with open(os.path.join(folder, name), errors='replace') as f:
                    hits = sum(1 for line in f if text in line)
                if hits:
                    found[name] = hits
        total = sum(found.values())
        if total >= count or time.time() >= deadline:
            break
        time.sleep(1.0)
    where = ', '.join('%s: %d' % item for item in found.items()) or 'nowhere'
    numbers = '%r %d time(s) in the commands\' output (%s)' % (text, total, where)
    if total < count:
        raise CheckFailed('%r appeared %d time(s), the row expects %d' % (text, total, count), numbers)
    return numbers


def check_floor(check, row):
    """The model stands on the floor: its height (get_model_state) against the world's highest collision
    surface under it no higher than `below` (floor.py, read from the world file, its models and meshes), within
    `tolerance` m. `offset`: the model's origin above its contact points when it rests (0 for a base_footprint)."""
    import rospkg
    from gazebo_msgs.srv import GetModelState
    getter = service('/gazebo/get_model_state', GetModelState)
    model = check.get('model', row.get('model'))
    deadline = time.time() + float(row.get('ready_timeout', 120))
    while not getter(model_name=model, relative_entity_name='').success:  # a model a later command spawns
        if time.time() > deadline:
            raise CheckFailed('model %r not in the world after %.0f s' % (model, float(row.get('ready_timeout', 120))))
        time.sleep(1.0)
    sim_sleep(float(check.get('settle', 1.0)))
    reply = getter(model_name=model, relative_entity_name='')
    if not reply.success:
        raise CheckFailed('get_model_state(%s): %s' % (model, reply.status_message))
    p = reply.pose.position
    path = resolve_find(check['world'])
    world = floor.WorldCollisions(path, model_paths(), exported_paths('gazebo_media_path', 'GAZEBO_RESOURCE_PATH'),
                        rospkg.RosPack().get_path)
    below = float(check.get('below', 0.5))
    height, surface = world.height_at(p.x, p.y, below)
    tol, offset = float(check['tolerance']), float(check.get('offset', 0.0))
    if height is None:
        raise CheckFailed('no collision surface of %s under (%.2f, %.2f) below z %.2f' % (
            os.path.basename(path), p.x, p.y, below), '%s at z %.4f' % (model, p.z))
    numbers = '%s at (%.2f, %.2f) z %.4f m; floor %.4f m there (%s)%s; off by %.4f (tolerance %.3f)' % (
        model, p.x, p.y, p.z, height, surface, ', offset %.3f' % offset if offset else '',
        p.z - offset - height, tol)
    if world.notes:
        numbers += '; ' + '; '.join(world.notes[:3]) + (' (+%d)' % (len(world.notes) - 3) if len(world.notes) > 3
                                                          else '')
    if abs(p.z - offset - height) > tol:
        raise CheckFailed('%s at z %.4f m, the floor under it at %.4f m (%s)' % (model, p.z, height, surface), numbers)
    return numbers


def check_map(check, row):
    """SLAM: drives `route` ([vx, wz, sim seconds] segments on `cmd_topic`), waits for the map, then judges the map
    on `map_topic` against the world file at the laser's `height` (slam_map.py): the share of occupied cells within
    `tolerance` m of the world's walls at least `on_walls`, the free area at least `explored` of the area the walls
    enclose. The map is placed in the world by the robot's pose in both (ground truth, and the map-to-`base_frame`
    transform)."""
    import rospkg
    import tf2_ros
    from gazebo_msgs.srv import GetModelState
    from corpus import slam_map
    getter = service('/gazebo/get_model_state', GetModelState)
    model = check.get('model', row.get('model'))
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    cmd = Commander(dict(check, vx=0.0, wz=0.0))
    try:
        sim_sleep(float(check.get('settle', 2.0)))
        for vx, wz, seconds in check['route']:
            cmd.msg.linear.x, cmd.msg.angular.z = float(vx), float(wz)
            sim_sleep(float(seconds))
        cmd.msg.linear.x = cmd.msg.angular.z = 0.0
        sim_sleep(float(check.get('map_wait', 6.0)))  # the SLAM node's next map update, with the robot at rest
    finally:
        cmd.stop()
    grid = message(check['map_topic'], 'nav_msgs/OccupancyGrid')
    try:
        seen = buffer.lookup_transform(grid.header.frame_id, check['base_frame'], rospy.Time(0), rospy.Duration(10.0))
    except tf2_ros.TransformException as err:
        raise CheckFailed('no transform %s -> %s: %s' % (grid.header.frame_id, check['base_frame'], err))
    x, y, yaw, _ = model_pose(getter, model)
    mx, my, myaw = seen.transform.translation.x, seen.transform.translation.y, yaw_of(seen.transform.rotation)
    turn = yaw - myaw  # world_from_map = world_from_base * inverse(map_from_base)
    world_from_map = (x - (math.cos(turn) * mx - math.sin(turn) * my), y - (math.sin(turn) * mx + math.cos(turn) * my),
                      turn)
    info = grid.info
    origin = (info.origin.position.x, info.origin.position.y, yaw_of(info.origin.orientation))
    occupied = slam_map.cells(grid.data, info.width, info.height, info.resolution, origin, world_from_map)
    free = slam_map.cells(grid.data, info.width, info.height, info.resolution, origin, world_from_map, False)
    media = exported_paths('gazebo_media_path', 'GAZEBO_RESOURCE_PATH')
    world = floor.WorldCollisions(resolve_find(check['world']), model_paths(), media, rospkg.RosPack().get_path)
    walls = slam_map.outline(world, float(check['height']))
    on_walls, area, enclosed = slam_map.judge(occupied, free, info.resolution, walls, float(check['tolerance']))
    explored = area / enclosed if enclosed else 0.0
    numbers = ('%d occupied cells, %.1f %% within %.2f m of the walls at z %.2f (at least %.0f %%); free %.2f m^2 of '
               '%.2f m^2 the walls enclose, %.1f %% (at least %.0f %%); %dx%d cells of %.3f m' % (
                   len(occupied), 100 * on_walls, float(check['tolerance']), float(check['height']),
                   100 * float(check['on_walls']), area, enclosed, 100 * explored, 100 * float(check['explored']),
                   info.width, info.height, info.resolution))
    problems = []
    if on_walls < float(check['on_walls']):
        problems.append('%.1f %% of the occupied cells on the walls' % (100 * on_walls))
    if explored < float(check['explored']):
        problems.append('%.1f %% of the area explored' % (100 * explored))
    if problems:
        raise CheckFailed('; '.join(problems), numbers)
    return numbers


def _map_in_world(check, grid):
    """(map frame's pose in the world, the map as map_registration.Grid, numbers): the map on `map_topic` placed
    on the world file's walls cut at the laser's `height` (map_registration.py)."""
    import rospkg
    from corpus import map_registration, slam_map
    info = grid.info
    served = map_registration.Grid(grid.data, info.width, info.height, info.resolution,
                                   (info.origin.position.x, info.origin.position.y, yaw_of(info.origin.orientation)))
    media = exported_paths('gazebo_media_path', 'GAZEBO_RESOURCE_PATH')
    world = floor.WorldCollisions(resolve_find(check['world']), model_paths(), media, rospkg.RosPack().get_path)
    walls = slam_map.outline(world, float(check['height']))
    try:
        found = map_registration.register(map_registration.occupied(served), walls, float(check.get('map_tolerance',
                                                                                                    0.1)))
    except map_registration.NoMatch as err:
        raise CheckFailed('the map is nowhere in %s: %s' % (os.path.basename(check['world']), err))
    other = found.runner_up
    numbers = ('map frame at (%.3f, %.3f, %.1f deg) in the world: %.1f %% of its %d occupied cells within %.2f m of '
               'the walls at z %.3f, mean %.3f m%s' % (
                   found.x, found.y, math.degrees(found.yaw), 100 * found.on_walls, found.cells, found.tolerance,
                   float(check['height']), found.mean_distance,
                   ' (next best placement: %.1f %% at %.0f deg)' % (100 * other.on_walls, math.degrees(other.yaw))
                   if other else ''))
    return found[:3], served, numbers


def check_navigation(check, row):
    """Navigation in a map of the package's own (map_server, amcl, move_base), as the tutorial's user does it:
    1. places the map on `map_topic` in the world (_map_in_world) to carry the ground truth into the map frame;
    2. the initial pose (nav_steps.initial_pose): a 2D Pose Estimate at the ground truth, or amcl's launch default;
    3. drives `route` (amcl updates only after update_min_d / update_min_a of motion), then /amcl_pose within
       `localisation_tolerance` m in x-y of the ground truth at its stamp;
    4. sends each of `goals` ([x, y, yaw], map frame; in free cells at least `min_clearance` m from the map's walls)
       to the `move_base` action, which must succeed within `goal_timeout` sim s; then amcl's pose (TF map ->
       `base_frame`: amcl's last estimate carried on by the odometry, the pose move_base itself judges) within
       move_base's own goal tolerances (DWAPlannerROS's on the parameter server, else the row's, said), and the
       ground truth within xy tolerance + localisation tolerance (amcl's own error on top of move_base's)."""
    import actionlib
    import tf2_ros
    from gazebo_msgs.srv import GetModelState
    from corpus import map_registration, nav_steps, navigation
    problems = navigation.input_problems(check)
    if problems:
        raise CheckFailed('; '.join(problems))
    try:
        from move_base_msgs.msg import MoveBaseAction
    except ImportError as err:
        raise CheckFailed('move_base_msgs cannot be imported (%s): navigation_msgs comes from make deps' % err)
    getter = service('/gazebo/get_model_state', GetModelState)
    model, tolerance = check.get('model', row.get('model')), float(check['localisation_tolerance'])
    grid = message(check.get('map_topic', '/map'), 'nav_msgs/OccupancyGrid', 60.0)  # map_server: a latched map
    frame = grid.header.frame_id or 'map'
    place, served, numbers = _map_in_world(check, grid)
    goals = [tuple(float(v) for v in g) for g in check['goals']]
    problems, clearances = navigation.goal_problems(served, goals, float(check.get('min_clearance', 0.0)))
    if problems:
        raise CheckFailed('; '.join(problems), numbers)
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    amcl = Latest(check.get('amcl_topic', '/amcl_pose'), 'geometry_msgs/PoseWithCovarianceStamped')
    to_map = map_registration.inverse(place)
    spawned = map_registration.compose(to_map, model_pose(getter, model)[:3])
    numbers += '; ' + nav_steps.initial_pose(check, spawned, frame)
    start = rospy.get_rostime().to_sec()
    history = nav_steps.drive_sampled(check, getter, model, to_map)
    seen = amcl.msg
    if seen is None or seen.header.stamp.to_sec() < start:
        raise CheckFailed('no %s since the initial pose: amcl did not update while the robot moved' % (
            check.get('amcl_topic', '/amcl_pose')), numbers)
    pose, stamp = seen.pose.pose, seen.header.stamp.to_sec()
    truth = navigation.nearest_in_time(history, stamp)
    problems, said = navigation.judge_localisation((pose.position.x, pose.position.y, yaw_of(pose.orientation)),
                                                   truth, tolerance)
    numbers += '; localised: %s (amcl at %.1f s sim, the ground truth %.2f s from it)' % (said, stamp,
                                                                                          abs(truth[3] - stamp))
    if problems:
        raise CheckFailed('; '.join(problems), numbers)
    xy_tol, yaw_tol, source = navigation.goal_tolerances(
        rospy.get_param('/move_base/DWAPlannerROS/xy_goal_tolerance', None),
        rospy.get_param('/move_base/DWAPlannerROS/yaw_goal_tolerance', None), check)
    numbers += '; goal tolerances %.3f m, %.3f rad from %s' % (xy_tol, yaw_tol, source)
    client = actionlib.SimpleActionClient(check.get('action', 'move_base'), MoveBaseAction)
    if not client.wait_for_server(rospy.Duration(60.0)):
        raise CheckFailed('action server %s not up in 60 s' % check.get('action', 'move_base'), numbers)
    for i, (goal, clearance) in enumerate(zip(goals, clearances), 1):
        state, seconds, text = nav_steps.reach(client, goal, frame, float(check['goal_timeout']))
        numbers += '; goal %d (%.2f, %.2f, %.2f; %.2f m from the walls): %s in %.1f s' % (
            i, goal[0], goal[1], goal[2], clearance, state, seconds)
        if state != 'SUCCEEDED':
            raise CheckFailed('goal %d: move_base %s after %.1f s of sim time (%s)' % (i, state, seconds, text),
                              numbers)
        sim_sleep(0.5)
        localised = nav_steps.tf_pose(buffer, frame, check.get('base_frame', 'base_footprint'))
        truth = map_registration.compose(to_map, model_pose(getter, model)[:3])
        problems, said = navigation.judge_goal(goal, localised, truth, xy_tol, yaw_tol, tolerance)
        numbers += ', ' + said
        if problems:
            raise CheckFailed('goal %d: %s' % (i, '; '.join(problems)), numbers)
    return numbers


KINDS = {'controllers': check_controllers, 'drive': check_drive, 'joint_position': check_joint_position,
         'trajectory': check_trajectory, 'gripper': check_gripper, 'sensors': check_sensors, 'world': check_world,
         'floor': check_floor, 'map': check_map, 'navigation': check_navigation,
         'plugin_output': check_plugin_output, 'flight': check_flight, 'topics_agree': check_topics_agree}


def run(row):
    results = []
    try:
        wait_ready(row)
        ready = None
    except CheckFailed as err:
        ready = str(err)
    for check in row['checks']:
        start = time.time()
        entry = {'kind': check['kind'], 'from': check.get('from', '')}
        if ready:
            entry.update(ok=False, numbers='', reason='not ready: ' + ready)
        else:
            try:
                entry.update(ok=True, numbers=KINDS[check['kind']](check, row), reason='')
            except CheckFailed as err:
                entry.update(ok=False, numbers=err.numbers, reason=str(err))
            except Exception as err:  # a check that crashed is a failed check, with its cause
                entry.update(ok=False, numbers='', reason='%s: %s' % (type(err).__name__, err))
                traceback.print_exc()
        entry['seconds'] = round(time.time() - start, 1)
        print('corpus check %s: %s %s' % (entry['kind'], 'ok' if entry['ok'] else 'FAIL',
                                          entry['numbers'] or entry['reason']), flush=True)
        results.append(entry)
    return results


def main():
    with open(sys.argv[1]) as f:
        row = json.load(f)
    rospy.init_node('racebot_corpus_checks', anonymous=True, disable_signals=True)
    results = run(row)
    with open(sys.argv[2], 'w') as f:
        json.dump(results, f, indent=2)
    rospy.signal_shutdown('done')


if __name__ == '__main__':
    main()

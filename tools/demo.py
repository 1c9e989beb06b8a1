#!/usr/bin/env python3
"""make demo: the racebot drives a scripted route through the room, headless, draws its path and, with gmapping,
the map it made.

Starts `roslaunch racebot_gazebo racebot.launch gui:=false teleop:=false` on a free port, waits
for the seven controllers, then sends AckermannDriveStamped commands on /ackermann_cmd_mux/output
(as a user's `rostopic pub` would) following a route keyed to simulated time: straight, left arc,
right arc, straight, reverse (about 13 s of sim time). The path comes from /gazebo/model_states.
Prints the distance driven and the final pose, and writes out/demo/demo_path.png (the path over
the room's walls and objects, seen from above) and out/demo/demo_path.json.

SLAM, when gmapping is found (rospack, in this shell or in make deps' underlay, docs/DEPS.md): racebot.launch runs
with odometry:=true and `roslaunch racebot_gazebo gmapping.launch` beside it; the car drives once gmapping has
published its first /map, and after the route the demo waits for a map made with the car at rest. The map is placed
in the world by the tf map -> odom: gazebo_odometry's odom is the world frame (it reports the world pose of
racebot::base_footprint from /gazebo/link_states, not a pose relative to the spawn), and gmapping starts its map
frame on the odom frame, correcting it as it matches scans. Prints the map's size, its occupied cells and the share
of them within TOLERANCE of the room's walls at the laser's height (tools/corpus/slam_map.py, as make corpus's `map`
check judges TurtleBot3's map), and writes out/demo/demo_map.png (the map under the path and the walls). Without
gmapping: one line saying how to get it, and the path alone.
"""
import argparse
import json
import math
import os
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import common, plot  # noqa: E402  (tools/bench: process and PNG helpers)

REPO = common.REPO
WORLD = os.path.join(REPO, 'racebot_gazebo', 'worlds', 'room_mini.world')
SPEED = 0.4  # m/s
STEER = 0.3  # rad; turning radius wheelbase / tan(0.3) = 0.84 m
# (what, speed m/s, steering rad, sim seconds): fits the free floor around the spawn point, clear of
# the warehouse robot ahead (x 1.85 .. 2.4, y < 0.05), the walls at y = 2.13 and x = 4.0 and the wide
# cinder block at (3.69, 1.21) (0.39 m square, 0.14 m high: below the laser, which passes over it at
# 0.17 m). The car ends the second straight near x 2.6, its front 0.7 m short of the block; the
# route of 2.5 s straights and 7.5 s of reverse drove into it, and the car climbed it and tipped
# over backwards onto its roof. The arcs overshoot (the steering turns in time; more on a loaded
# machine, where a command is kept longer), so the right arc is shorter than the left one: the car
# reverses 2 m from y 1.3 heading about 5 degrees off +x; 20 degrees off (a 3.3 s right arc under
# load) would still leave its side 0.07 m clear of the wall at y = 2.13.
ROUTE = [('straight', SPEED, 0.0, 1.0),
         ('left arc', SPEED, STEER, 3.3),
         ('right arc', SPEED, -STEER, 3.0),
         ('straight', SPEED, 0.0, 0.5),
         ('reverse', -SPEED, 0.0, 5.0)]
TIPPED = 30.0  # deg: a tilt the car does not reach on the floor (it drives level, to 0.1 deg)
CONTROLLERS = 7
# The laser's height above the floor, where its scan cuts the world: base_link 0.032 (the wheel radius) above
# base_footprint, lidar 0.12377 above base_link (racecar.xacro), the ray sensor's <pose> 0.0124 above lidar
# (racecar.gazebo).
LASER_HEIGHT = 0.032 + 0.12377 + 0.0124
TOLERANCE = 0.1  # m: an occupied cell this close to a wall is on it (two of gmapping.launch's 5 cm cells)
MAP_TIMEOUT = 90  # wall s for gmapping's first map, and for a map made after the car stopped
GMAPPING_HINT = ('racebot demo: gmapping not found, so no map (make deps ARGS=gmapping builds it, docs/DEPS.md; '
                 'make demo then finds it); drawing the path only')


def wall_footprints(world_file):
    """2-D outlines (lists of corner points) of every box, cylinder and sphere in the world."""
    from racebot_sim_bridge.description import sdf_reader
    world = sdf_reader.load_world(world_file)
    shapes = []
    for model in world.models:
        for link in model.links:
            for col in link.collisions:
                (x, y, _), q = model.world_pose_of(link, col)
                yaw = math.atan2(2 * (q[3] * q[2] + q[0] * q[1]), 1 - 2 * (q[1] ** 2 + q[2] ** 2))
                s = col.shape
                if s.kind == 'box':
                    hx, hy = s.size[0] / 2, s.size[1] / 2
                    corners = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy), (-hx, -hy)]
                elif s.kind in ('cylinder', 'sphere'):
                    corners = [(s.radius * math.cos(a * math.pi / 8), s.radius * math.sin(a * math.pi / 8))
                               for a in range(17)]
                else:
                    continue
                c, sn = math.cos(yaw), math.sin(yaw)
                shapes.append([(x + c * px - sn * py, y + sn * px + c * py) for px, py in corners])
    return shapes


def draw(path_png, shapes, path):
    near = [s for s in shapes if all(abs(x) < 50 and abs(y) < 50 for x, y in s)]  # not the ground plane
    plot.room_path(path_png, near, path)


def _finds(package, env):
    return subprocess.run(['rospack', 'find', package], env=env, stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL).returncode == 0


def gmapping_env():
    """(environment, where) to run gmapping in: this shell's when rospack finds gmapping in it; else, when make deps'
    underlay has it, this shell's with the underlay sourced and racebot's devel space on top again (the underlay
    sources the racebot it was built on); else (None, None)."""
    if _finds('gmapping', os.environ):
        return dict(os.environ), 'this shell'
    cache = os.environ.get('RACEBOT_DEPS_CACHE') or os.path.expanduser(os.path.join('~', '.cache', 'racebot', 'deps'))
    setup = os.path.join(cache, 'ws', 'devel_isolated', 'setup.bash')
    if not os.path.isfile(setup):
        return None, None
    script = 'source %s >/dev/null 2>&1; source %s --extend >/dev/null 2>&1; env -0' % (
        shlex.quote(setup), shlex.quote(os.path.join(REPO, 'devel', 'setup.bash')))
    done = subprocess.run(['bash', '-c', script], stdout=subprocess.PIPE, env=os.environ)
    env = dict(item.split('=', 1) for item in done.stdout.decode().split('\0') if '=' in item)
    return (env, os.path.dirname(setup)) if _finds('gmapping', env) else (None, None)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--out', default=os.path.join(REPO, 'out', 'demo'), help='folder for the PNGs and JSON')
    args = parser.parse_args()
    started = time.monotonic()
    common.ensure_dir(args.out)
    env, where = gmapping_env()
    if env is None:
        print(GMAPPING_HINT, flush=True)
    else:
        os.environ.update(env)
        print('racebot demo: gmapping from %s: mapping the room as the car drives' % where, flush=True)
    port = common.free_port()
    os.environ.update(common.ros_env(port))
    launch = common.roslaunch(['racebot_gazebo', 'racebot.launch', 'gui:=false', 'teleop:=false']
                              + (['odometry:=true'] if env is not None else []), port,
                              os.path.join(args.out, 'roslaunch.log'))
    mapping = Mapping(port, os.path.join(args.out, 'gmapping.log')) if env is not None else None
    try:
        return drive(args.out, launch, mapping)
    except common.BenchError as err:
        print('demo: %s' % err, file=sys.stderr)
        return 1
    finally:
        if mapping is not None:
            mapping.stop()
        launch.stop()
        print('racebot demo: %.0f s of wall time' % (time.monotonic() - started))


class Mapping:
    """gmapping.launch beside the simulator: its /map and its tf map -> odom (read from /tf as slam_gmapping
    publishes it: a tf2 buffer here would print TF_REPEATED_DATA warnings for transforms published twice with one
    stamp, which gmapping does when sim time runs slower than its 20 Hz of wall time)."""

    def __init__(self, port, log_path):
        self.port, self.log_path = port, log_path
        self.launch = None
        self.grid = None
        self.correction = None  # the latest map -> odom

    def start(self):
        """Once the simulator's nodes run (its master, the clock, the tf tree): gmapping.launch, and listen."""
        import rospy
        from nav_msgs.msg import OccupancyGrid
        from tf2_msgs.msg import TFMessage
        rospy.Subscriber('/map', OccupancyGrid, lambda m: setattr(self, 'grid', m), queue_size=1)
        rospy.Subscriber('/tf', TFMessage, self._on_tf, queue_size=50)
        self.launch = common.roslaunch(['racebot_gazebo', 'gmapping.launch'], self.port, self.log_path)

    def _on_tf(self, msg):
        for t in msg.transforms:
            if t.header.frame_id.lstrip('/') == 'map' and t.child_frame_id.lstrip('/') == 'odom':
                self.correction = t.transform

    def wait(self, after, what):
        """A map stamped at `after` (sim s) or later."""
        common.wait_for(lambda: self.grid is not None and self.grid.header.stamp.to_sec() >= after, MAP_TIMEOUT,
                        what, self.launch)
        return self.grid

    def map_from_odom(self):
        """(x, y, yaw) of the odom frame in the map frame: gmapping's correction of the odometry."""
        common.wait_for(lambda: self.correction is not None, 10, 'the tf map -> odom from slam_gmapping', self.launch)
        t = self.correction
        q = t.rotation
        return t.translation.x, t.translation.y, math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))

    def stop(self):
        if self.launch is not None:
            self.launch.stop()


def drive(out, launch, mapping=None):
    import rospy
    from ackermann_msgs.msg import AckermannDriveStamped
    from controller_manager_msgs.srv import ListControllers
    from gazebo_msgs.msg import ModelStates
    from rosgraph_msgs.msg import Clock

    common.wait_for(lambda: common.master_online(int(os.environ['ROS_MASTER_URI'].rsplit(':', 1)[1])), 60,
                    'the ROS master', launch)
    rospy.init_node('racebot_demo', disable_signals=True)
    state = {'clock': None, 'pose': None, 'tilt': 0.0}
    path = []

    def on_states(msg):
        if 'racebot' in msg.name and state['clock'] is not None:
            p = msg.pose[msg.name.index('racebot')]
            q = p.orientation
            yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
            state['pose'] = (p.position.x, p.position.y, yaw)
            state['tilt'] = max(state['tilt'], math.degrees(math.acos(max(-1.0, 1 - 2 * (q.x ** 2 + q.y ** 2)))))
            if not path or state['clock'] - path[-1][0] >= 0.05:
                path.append((state['clock'], p.position.x, p.position.y, yaw))

    rospy.Subscriber('/clock', Clock, lambda m: state.__setitem__('clock', m.clock.to_sec()), queue_size=1)
    rospy.Subscriber('/gazebo/model_states', ModelStates, on_states, queue_size=1)
    pub = rospy.Publisher('/ackermann_cmd_mux/output', AckermannDriveStamped, queue_size=10)
    srv = '/racebot/controller_manager/list_controllers'
    common.wait_for(lambda: _running(srv, ListControllers) == CONTROLLERS, 90, 'the seven controllers', launch)
    common.wait_for(lambda: pub.get_num_connections() > 0 and state['pose'] is not None, 30,
                    'servo_commands and /gazebo/model_states', launch)
    if mapping is not None:
        mapping.start()
        mapping.wait(0.0, "gmapping's first map (%s)" % mapping.log_path)
    del path[:]
    state['tilt'] = 0.0
    print('racebot demo: driving %s' % ', '.join('%s %.1f s' % (w, d) for w, _, _, d in ROUTE), flush=True)
    for what, speed, steer, duration in ROUTE:
        end = state['clock'] + duration
        cmd = AckermannDriveStamped()
        cmd.header.frame_id = 'base_link'
        cmd.drive.speed, cmd.drive.steering_angle = speed, steer
        while state['clock'] < end:
            common.wait_for(lambda: launch.alive(), 1, 'the simulation', launch)
            pub.publish(cmd)  # repeated, like a teleop, at ~10 Hz of wall time
            time.sleep(0.1)
    pub.publish(AckermannDriveStamped())  # stop
    start_clock = state['clock']
    common.wait_for(lambda: state['clock'] >= start_clock + 1.0, 30, 'the car to stop', launch)
    code = report(out, path, state['tilt'])
    if mapping is None or code:
        return code
    grid = mapping.wait(start_clock + 1.0, 'a map made with the car at rest (%s)' % mapping.log_path)
    return report_map(out, path, grid, mapping.map_from_odom())


def _running(srv, cls):
    import rospy
    try:
        rospy.wait_for_service(srv, timeout=0.5)
        return sum(c.state == 'running' for c in rospy.ServiceProxy(srv, cls)().controller)
    except (rospy.ROSException, rospy.ServiceException):
        return 0


def report(out, path, tilt=0.0):
    if len(path) < 2:
        print('demo: no poses were received from /gazebo/model_states', file=sys.stderr)
        return 1
    distance = sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(path, path[1:]))
    t, x, y, yaw = path[-1]
    png = os.path.join(out, 'demo_path.png')
    draw(png, wall_footprints(WORLD), path)
    with open(os.path.join(out, 'demo_path.json'), 'w') as f:
        json.dump({'route': ROUTE, 'distance_m': distance, 'final_pose': {'x': x, 'y': y, 'yaw': yaw},
                   'max_tilt_deg': tilt, 'sim_seconds': t - path[0][0], 'path': path}, f, indent=1)
    print('racebot demo: drove %.2f m in %.1f s of sim time; final pose x %.2f m, y %.2f m, yaw %.1f deg'
          % (distance, t - path[0][0], x, y, math.degrees(yaw)))
    print('racebot demo: path over the room written to %s' % os.path.relpath(png, os.getcwd()))
    if tilt > TIPPED:
        print('demo: the car tipped over on the way (tilted %.0f deg): something in its path?' % tilt, file=sys.stderr)
        return 1
    return 0


def world_from_map(map_from_odom):
    """(x, y, yaw) of the map frame in the world, from gmapping's tf map -> odom (x, y, yaw of the odom frame in the
    map frame): the odom frame is the world frame (gazebo_odometry), so this is the inverse of map -> odom."""
    x, y, yaw = map_from_odom
    c, s = math.cos(yaw), math.sin(yaw)
    return -(c * x + s * y), -(-s * x + c * y), -yaw


def map_numbers(grid, in_world, walls, tolerance=TOLERANCE):
    """What the demo says of a map: grid {'data', 'width', 'height', 'resolution', 'origin': (x, y, yaw) of its
    corner in the map frame}, in_world the map frame's (x, y, yaw) in the world, walls (N x 2) the world's walls at
    the laser's height. -> {'width', 'height', 'resolution', 'occupied', 'on_walls', 'free_m2'} (slam_map)."""
    from corpus import slam_map
    args = (grid['data'], grid['width'], grid['height'], grid['resolution'], grid['origin'], in_world)
    occupied, free = slam_map.cells(*args), slam_map.cells(*args, occupied=False)
    on_walls, free_m2, _ = slam_map.judge(occupied, free, grid['resolution'], walls, tolerance)
    return {'width': grid['width'], 'height': grid['height'], 'resolution': grid['resolution'],
            'occupied': len(occupied), 'on_walls': on_walls, 'free_m2': free_m2}


def report_map(out, path, msg, map_from_odom):
    """The map (a nav_msgs/OccupancyGrid) judged against the room's walls, printed and drawn."""
    from corpus import floor, slam_map
    info, q = msg.info, msg.info.origin.orientation
    grid = {'data': msg.data, 'width': info.width, 'height': info.height, 'resolution': info.resolution,
            'origin': (info.origin.position.x, info.origin.position.y,
                       math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2)))}
    in_world = world_from_map(map_from_odom)
    walls = slam_map.outline(floor.WorldCollisions(WORLD, []), LASER_HEIGHT)
    numbers = map_numbers(grid, in_world, walls)
    res = numbers['resolution']
    print('racebot demo: map %d x %d cells of %.2f m (%.1f x %.1f m), %d occupied, %.1f %% of them within %.2f m of '
          "the room's walls at the laser's height (%.2f m); %.1f m^2 free; map -> odom (%.3f m, %.3f m, %.2f deg)"
          % (numbers['width'], numbers['height'], res, numbers['width'] * res, numbers['height'] * res,
             numbers['occupied'], 100 * numbers['on_walls'], TOLERANCE, LASER_HEIGHT, numbers['free_m2'],
             map_from_odom[0], map_from_odom[1], math.degrees(map_from_odom[2])))
    x, y, yaw = in_world
    c, s = math.cos(yaw), math.sin(yaw)
    ox, oy, oyaw = grid['origin']
    placed = dict(grid, origin=(x + c * ox - s * oy, y + s * ox + c * oy, yaw + oyaw))
    png = os.path.join(out, 'demo_map.png')
    plot.room_map(png, placed, walls, path, 'racebot demo: the map gmapping made (%.0f %% of its %d occupied cells '
                  'on the walls), and the path' % (100 * numbers['on_walls'], numbers['occupied']))
    with open(os.path.join(out, 'demo_map.json'), 'w') as f:
        json.dump(dict(numbers, tolerance_m=TOLERANCE, laser_height_m=LASER_HEIGHT, map_from_odom=map_from_odom),
                  f, indent=1)
    print('racebot demo: map under the path written to %s' % os.path.relpath(png, os.getcwd()))
    return 0


if __name__ == '__main__':
    sys.exit(main())

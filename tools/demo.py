#!/usr/bin/env python3
"""make demo: the racebot drives a scripted route through the room, headless, and draws its path.

Starts `roslaunch racebot_gazebo racebot.launch gui:=false teleop:=false` on a free port, waits
for the seven controllers, then sends AckermannDriveStamped commands on /ackermann_cmd_mux/output
(as a user's `rostopic pub` would) following a route keyed to simulated time: straight, left arc,
right arc, straight, reverse (about 19 s of sim time). The path comes from /gazebo/model_states.
Prints the distance driven and the final pose, and writes out/demo/demo_path.png (the path over
the room's walls and objects, seen from above) and out/demo/demo_path.json.
"""
import argparse
import json
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import common, plot  # noqa: E402  (tools/bench: process and PNG helpers)

REPO = common.REPO
WORLD = os.path.join(REPO, 'racebot_gazebo', 'worlds', 'room_mini.world')
SPEED = 0.4  # m/s
STEER = 0.3  # rad; turning radius wheelbase / tan(0.3) = 0.84 m
# (what, speed m/s, steering rad, sim seconds): fits the free floor around the spawn point, clear of
# the warehouse robot ahead (x > 1.85) and the walls at y = 2.21 and x = 4.07.
ROUTE = [('straight', SPEED, 0.0, 2.5),
         ('left arc', SPEED, STEER, 3.3),
         ('right arc', SPEED, -STEER, 3.3),
         ('straight', SPEED, 0.0, 2.5),
         ('reverse', -SPEED, 0.0, 7.5)]
CONTROLLERS = 7


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


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--out', default=os.path.join(REPO, 'out', 'demo'), help='folder for the PNG and JSON')
    args = parser.parse_args()
    common.ensure_dir(args.out)
    port = common.free_port()
    os.environ.update(common.ros_env(port))
    launch = common.roslaunch(['racebot_gazebo', 'racebot.launch', 'gui:=false', 'teleop:=false'], port,
                              os.path.join(args.out, 'roslaunch.log'))
    try:
        return drive(args.out, launch)
    except common.BenchError as err:
        print('demo: %s' % err, file=sys.stderr)
        return 1
    finally:
        launch.stop()


def drive(out, launch):
    import rospy
    from ackermann_msgs.msg import AckermannDriveStamped
    from controller_manager_msgs.srv import ListControllers
    from gazebo_msgs.msg import ModelStates
    from rosgraph_msgs.msg import Clock

    common.wait_for(lambda: common.master_online(int(os.environ['ROS_MASTER_URI'].rsplit(':', 1)[1])), 60,
                    'the ROS master', launch)
    rospy.init_node('racebot_demo', disable_signals=True)
    state = {'clock': None, 'pose': None}
    path = []

    def on_states(msg):
        if 'racebot' in msg.name and state['clock'] is not None:
            p = msg.pose[msg.name.index('racebot')]
            q = p.orientation
            yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
            state['pose'] = (p.position.x, p.position.y, yaw)
            if not path or state['clock'] - path[-1][0] >= 0.05:
                path.append((state['clock'], p.position.x, p.position.y, yaw))

    rospy.Subscriber('/clock', Clock, lambda m: state.__setitem__('clock', m.clock.to_sec()), queue_size=1)
    rospy.Subscriber('/gazebo/model_states', ModelStates, on_states, queue_size=1)
    pub = rospy.Publisher('/ackermann_cmd_mux/output', AckermannDriveStamped, queue_size=10)
    srv = '/racebot/controller_manager/list_controllers'
    common.wait_for(lambda: _running(srv, ListControllers) == CONTROLLERS, 90, 'the seven controllers', launch)
    common.wait_for(lambda: pub.get_num_connections() > 0 and state['pose'] is not None, 30,
                    'servo_commands and /gazebo/model_states', launch)
    del path[:]
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
    return report(out, path)


def _running(srv, cls):
    import rospy
    try:
        rospy.wait_for_service(srv, timeout=0.5)
        return sum(c.state == 'running' for c in rospy.ServiceProxy(srv, cls)().controller)
    except (rospy.ROSException, rospy.ServiceException):
        return 0


def report(out, path):
    if len(path) < 2:
        print('demo: no poses were received from /gazebo/model_states', file=sys.stderr)
        return 1
    distance = sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(path, path[1:]))
    t, x, y, yaw = path[-1]
    png = os.path.join(out, 'demo_path.png')
    draw(png, wall_footprints(WORLD), path)
    with open(os.path.join(out, 'demo_path.json'), 'w') as f:
        json.dump({'route': ROUTE, 'distance_m': distance, 'final_pose': {'x': x, 'y': y, 'yaw': yaw},
                   'sim_seconds': t - path[0][0], 'path': path}, f, indent=1)
    print('racebot demo: drove %.2f m in %.1f s of sim time; final pose x %.2f m, y %.2f m, yaw %.1f deg'
          % (distance, t - path[0][0], x, y, math.degrees(yaw)))
    print('racebot demo: path over the room written to %s' % os.path.relpath(png, os.getcwd()))
    return 0


if __name__ == '__main__':
    sys.exit(main())

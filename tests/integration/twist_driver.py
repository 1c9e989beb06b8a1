#!/usr/bin/env python3
"""A Twist publisher in its own process, as `rostopic pub -r 20` is: the fixture tests' Driver starts it.

It publishes the latest command read from stdin ("vx vy wz", or "none" for silence) on each topic named on its
command line at 20 Hz of wall time, till stdin closes. Its own process because the test node is busy (two /clock
subscriptions at 1000 Hz, /tf, the odometry): on a machine loaded three times over its cores, a publishing thread
there waited for the interpreter long enough that the controller's cmd_vel_timeout (0.25 s) braked a robot the
test was measuring (diff_drive_controller's forward speed 0.17 of 0.30 m/s). Alone, with no /clock subscription
(disable_rostime) and nothing else to run, it wakes on time.
"""
import sys
import threading
import time

import rospy
from geometry_msgs.msg import Twist

PERIOD = 0.05  # wall s


def parse(line):
    """The Twist of a command line, None for "none"; ValueError for anything else."""
    words = line.split()
    if words == ['none']:
        return None
    vx, vy, wz = (float(w) for w in words)
    t = Twist()
    t.linear.x, t.linear.y, t.angular.z = vx, vy, wz
    return t


def main(topics):
    rospy.init_node('twist_driver', anonymous=True, disable_rostime=True, disable_signals=True)
    pubs = [rospy.Publisher(topic, Twist, queue_size=1) for topic in topics]
    state = {'command': None, 'open': True}

    def read():
        for line in sys.stdin:
            state['command'] = parse(line)
        state['open'] = False

    threading.Thread(target=read, daemon=True).start()
    print('ready', flush=True)
    while state['open']:
        cmd = state['command']
        if cmd is not None:
            for pub in pubs:
                pub.publish(cmd)
        time.sleep(PERIOD)
    rospy.signal_shutdown('stdin closed')


if __name__ == '__main__':
    main(rospy.myargv(sys.argv)[1:])

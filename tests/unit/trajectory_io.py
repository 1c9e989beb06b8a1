"""The joint trajectory controller's I/O with its action server, a goal handle, and a goal."""
import rospy
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint


class IO:
    def __init__(self):
        self.topics, self.warnings, self.services, self.actions = {}, [], {}, {}

    def publisher(self, topic, cls, queue_size):
        return self.topics.setdefault(topic, Topic())

    def subscriber(self, topic, cls, callback):
        return self.topics.setdefault(topic, Topic(callback))

    def service(self, name, cls, handler):
        self.services[name] = handler
        return Topic()

    def action_server(self, ns, cls, goal_cb, cancel_cb):
        self.actions[ns] = (goal_cb, cancel_cb)
        return Topic()

    def stamp(self, t):
        return rospy.Time.from_sec(t)

    def warn_throttle(self, key, period, message):
        self.warnings.append(message)


class GoalHandle:
    """actionlib's ServerGoalHandle as the controller uses it, recording what it was told."""

    def __init__(self, goal):
        self.goal, self.status, self.result, self.feedback = goal, 'pending', None, []

    def get_goal(self):
        return self.goal

    def set_accepted(self, text=''):
        self.status = 'active'

    def set_rejected(self, result=None, text=''):
        self.status, self.result = 'rejected', result

    def set_canceled(self, result=None, text=''):
        self.status = 'canceled'

    def set_aborted(self, result=None, text=''):
        self.status, self.result = 'aborted', result

    def set_succeeded(self, result=None, text=''):
        self.status, self.result = 'succeeded', result

    def publish_feedback(self, feedback):
        self.feedback.append(feedback)


def trajectory(points, joints=('j1', 'j2')):
    t = JointTrajectory(joint_names=list(joints))
    for positions, seconds in points:
        t.points.append(JointTrajectoryPoint(positions=list(positions), time_from_start=rospy.Duration(seconds)))
    return t


class Topic:
    def __init__(self, callback=None):
        self.callback, self.messages = callback, []

    def publish(self, msg):
        self.messages.append(msg)

    def unregister(self):
        pass

"""The topics_agree check's comparison (tools/corpus/topics_agree.py): two messages field by field."""
import math

from nav_msgs.msg import Odometry

from corpus.topics_agree import differences, fields, moving_fields


def odometry(x=1.0, frame='world', covariance=0.0):
    msg = Odometry()
    msg.header.frame_id, msg.child_frame_id = frame, 'rotor'
    msg.pose.pose.position.x, msg.pose.pose.orientation.w = x, 1.0
    msg.twist.twist.angular.z = -0.25
    msg.pose.covariance = [covariance] * 36
    return msg


def test_every_leaf_is_named_by_its_path_arrays_by_index():
    names = dict(fields(odometry()))
    assert names['pose.pose.position.x'] == 1.0 and names['twist.twist.angular.z'] == -0.25
    assert names['header.frame_id'] == 'world' and 'pose.covariance.35' in names


def test_equal_messages_differ_by_nothing_and_the_publishers_counts_are_not_compared():
    assert differences(odometry(), odometry()) == (0.0, '', [])
    later = odometry()
    later.header.seq = 7  # what each publisher's transport sent before: not the plugin's
    assert differences(odometry(), later) == (0.0, '', [])


def test_the_largest_numeric_difference_and_its_field():
    largest, where, other = differences(odometry(1.0), odometry(1.0 + 3e-9))
    assert where == 'pose.pose.position.x' and math.isclose(largest, 3e-9, rel_tol=1e-6) and other == []


def test_strings_and_a_nan_on_one_side_are_differences_of_their_own():
    _, _, other = differences(odometry(frame='world'), odometry(frame='map'))
    assert other == ["header.frame_id: 'world' against 'map'"]
    _, _, other = differences(odometry(covariance=float('nan')), odometry())
    assert len(other) == 36
    assert differences(odometry(covariance=float('nan')), odometry(covariance=float('nan')))[2] == []


def test_the_fields_that_move_are_found_and_the_stamps_and_counts_are_not_motion():
    a, b = odometry(1.0), odometry(2.0)
    b.header.seq, b.header.stamp.nsecs = 3, 20000000
    assert moving_fields([a, b]) == ['pose.pose.position.x']
    assert moving_fields([a, odometry(1.0)]) == []

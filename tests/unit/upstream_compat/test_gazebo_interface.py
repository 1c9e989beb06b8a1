"""gazebo_ros.gazebo_interface's wait for a service, with rospy's wait_for_service replaced (no master):
a timeout is a clear error and False; a shutdown while waiting (Ctrl-C on spawn_model -gazebo_namespace
/nowhere, which waits for ever as upstream) reaches spawn_model's main as rospy's ROSInterruptException
instead of a TypeError from formatting the absent timeout.
"""
import pytest
import rospy

from gazebo_ros import gazebo_interface


def _raising(exc):
    def wait_for_service(service, timeout=None):
        raise exc
    return wait_for_service


@pytest.mark.parametrize('timeout', [None, 2.0])
def test_a_shutdown_while_waiting_is_rospys_interrupt(monkeypatch, timeout):
    monkeypatch.setattr(rospy, 'wait_for_service', _raising(rospy.ROSInterruptException('rospy shutdown')))
    with pytest.raises(rospy.ROSInterruptException):
        gazebo_interface._wait('/nowhere/spawn_urdf_model', timeout)


def test_a_timeout_is_logged_and_false(monkeypatch):
    logged = []
    monkeypatch.setattr(rospy, 'wait_for_service', _raising(rospy.ROSException('timeout exceeded')))
    monkeypatch.setattr(rospy, 'logerr', logged.append)
    assert gazebo_interface._wait('/nowhere/spawn_urdf_model', 2.0) is False
    assert '/nowhere/spawn_urdf_model did not appear within 2 s' in logged[0]
    assert '-gazebo_namespace' in logged[0]

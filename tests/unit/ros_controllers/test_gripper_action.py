"""gripper_action_controller's success and stall decision (checkForSuccess in noetic-devel's
gripper_action_controller_impl.h), as controllers/gripper_action.gripper_outcome makes it. No ROS master."""
from racebot_sim_bridge.ros_controllers.gripper_action_controller import gripper_outcome

TOL, STALL_V, STALL_T = 0.01, 0.001, 1.0


def test_within_tolerance_is_reached():
    assert gripper_outcome(0.009, 0.5, 3.0, 0.0, TOL, STALL_V, STALL_T) == ('reached', 0.0)
    assert gripper_outcome(-0.009, 0.0, 3.0, 0.0, TOL, STALL_V, STALL_T)[0] == 'reached'
    # the bound is strict, as upstream's fabs(error) < goal_tolerance
    assert gripper_outcome(0.01, 0.0, 0.5, 0.0, TOL, STALL_V, STALL_T)[0] is None


def test_moving_resets_the_stall_clock():
    assert gripper_outcome(0.05, 0.002, 7.0, 1.0, TOL, STALL_V, STALL_T) == (None, 7.0)
    assert gripper_outcome(0.05, -0.002, 7.0, 1.0, TOL, STALL_V, STALL_T) == (None, 7.0)


def test_standing_still_longer_than_the_timeout_is_a_stall():
    assert gripper_outcome(0.05, 0.0005, 1.9, 1.0, TOL, STALL_V, STALL_T) == (None, 1.0)
    assert gripper_outcome(0.05, 0.0005, 2.0001, 1.0, TOL, STALL_V, STALL_T) == ('stalled', 1.0)

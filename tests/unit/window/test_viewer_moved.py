"""The window's update filter (viewer_process.moved): every call into PyBullet's GUI client waits for a
frame, so only bodies that moved are posed; a body that moved, even slightly, must be."""
from racebot_sim_bridge.window.viewer_process import moved

KEY = ('racebot', 1)
POSE = ((0.0, 0.0, 0.1), (0.0, 0.0, 0.0, 1.0))
ENTRY = (KEY, [POSE], (0.0, 0.25))


def test_a_body_never_shown_is_posed():
    assert moved(None, ENTRY)


def test_the_same_entry_is_not_posed_again():
    assert not moved(ENTRY, (KEY, [POSE], (0.0, 0.25)))
    assert not moved(ENTRY, (KEY, [((0.00005, 0.0, 0.1), POSE[1])], (0.0, 0.25)))  # below 0.1 mm


def test_a_move_of_the_base_or_a_joint_is_posed():
    assert moved(ENTRY, (KEY, [((0.001, 0.0, 0.1), POSE[1])], (0.0, 0.25)))
    assert moved(ENTRY, (KEY, [(POSE[0], (0.0, 0.0, 0.001, 1.0))], (0.0, 0.25)))
    assert moved(ENTRY, (KEY, [POSE], (0.0, 0.2505)))


def test_a_respawned_body_is_posed_even_in_the_same_place():
    assert moved(ENTRY, (('racebot', 2), [POSE], (0.0, 0.25)))
    assert moved(ENTRY, (KEY, [POSE, POSE], (0.0, 0.25)))  # an extra body appeared

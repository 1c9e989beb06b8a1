"""Where the keyboard window goes beside the 3D window (racebot_gazebo.window_place.beside): to its right,
below it on a narrow screen, the screen's corner when neither fits. The X side runs in viewer.test."""

import pytest

from racebot_gazebo.window_place import GAP, beside, overlap

THREE_D = (0, 0, 1024, 768)  # PyBullet's window, where it always opens
KEYBOARD = (274, 174)        # the keyboard window's size (Tk, Xvfb's fonts)


@pytest.mark.parametrize('screen, where', [
    ((1920, 1080), (1024 + GAP, 0)),       # wide: to the right
    ((1280, 1024), (0, 768 + GAP)),        # 1280 is too narrow for 1024 + 274: below
    ((1024, 768), (1024 - 274, 768 - 174)),  # neither fits: the bottom right corner
    ((200, 100), (0, 0)),                  # a screen smaller than the window: its top left corner
])
def test_beside_the_3d_window(screen, where):
    assert beside(THREE_D, KEYBOARD, screen) == where


@pytest.mark.parametrize('screen', [(1920, 1080), (1280, 1024)])
def test_where_it_fits_it_is_apart_and_on_the_screen(screen):
    x, y = beside(THREE_D, KEYBOARD, screen)
    assert not overlap((x, y) + KEYBOARD, THREE_D)
    assert x + KEYBOARD[0] <= screen[0] and y + KEYBOARD[1] <= screen[1]


def test_a_3d_window_elsewhere_keeps_its_neighbour_level_with_it_and_on_the_screen():
    assert beside((100, 50, 640, 480), KEYBOARD, (1920, 1080)) == (740 + GAP, 50)
    assert beside((100, 1000, 640, 80), KEYBOARD, (1920, 1080)) == (740 + GAP, 1080 - 174)
    assert beside((1500, 50, 640, 480), KEYBOARD, (1920, 1080)) == (1500, 530 + GAP)
    assert beside((1800, 50, 100, 480), KEYBOARD, (1920, 1080)) == (1920 - 274, 530 + GAP)


def test_overlap():
    assert overlap((0, 0, 10, 10), (9, 9, 5, 5))
    assert overlap((2, 2, 3, 3), (0, 0, 10, 10))  # inside
    assert not overlap((0, 0, 10, 10), (10, 0, 5, 5))  # touching edges share no pixel
    assert not overlap((0, 0, 10, 10), (0, 10, 5, 5))
    assert not overlap((0, 0, 10, 10), (20, 20, 5, 5))

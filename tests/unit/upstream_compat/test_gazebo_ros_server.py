"""gazebo_ros.server.resource_path: gzserver puts gazebo_ros's folder (which holds worlds/empty.world)
first on GAZEBO_RESOURCE_PATH, as Gazebo's setup.sh puts its own share folder first. No ROS master."""
import os

import pytest

from gazebo_ros.server import resource_path


@pytest.mark.parametrize('current, expected', [
    (None, '/pkg'),
    ('', '/pkg'),
    ('/a', '/pkg:/a'),
    ('/a:/b', '/pkg:/a:/b'),
    ('/a:/pkg:/b', '/pkg:/a:/b'),  # once, first
    ('/pkg', '/pkg'),
    (':/a::', '/pkg:/a'),
])
def test_own_folder_first_once(current, expected):
    assert resource_path('/pkg', current) == expected.replace(':', os.pathsep)

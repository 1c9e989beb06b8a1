"""Shared fixtures of the unit tests: the racebot model rendered from its xacro, once per session.

The tests mirror racebot_sim_bridge's layout (one folder per subpackage; upstream_compat, tutorial, tools and
nodes for the rest). Some import another folder's test module for its fakes or worlds (test_controllers,
test_sensors_sim, test_plugin_namespace): every folder is on sys.path, so a test module has one name."""
import os
import sys
from pathlib import Path

import pytest
from hypothesis import settings

# The suite's property tests draw the same examples every run (derandomize): a failure is a defect found
# once and kept, never a run that fails one time in ten. To explore new examples, run pytest with
# HYPOTHESIS_PROFILE=explore; a failure found so goes in as an @example of its test.
settings.register_profile('suite', derandomize=True)
settings.register_profile('explore', derandomize=False)
settings.load_profile(os.environ.get('HYPOTHESIS_PROFILE', 'suite'))

REPO = Path(__file__).resolve().parents[2]
for _folder in sorted(Path(__file__).resolve().parent.iterdir()):
    if _folder.is_dir() and not _folder.name.startswith(('.', '_')) and str(_folder) not in sys.path:
        sys.path.append(str(_folder))
XACRO_FILE = REPO / 'racebot_description' / 'urdf' / 'ackermann' / 'racecar.xacro'


def render_racebot(pretty=True):
    """The racebot URDF as robot_description holds it (the xacro executable writes the pretty form);
    `$(find racebot_description)` resolves through ROS_PACKAGE_PATH, extended with this checkout."""
    import xacro
    old = os.environ.get('ROS_PACKAGE_PATH')
    os.environ['ROS_PACKAGE_PATH'] = os.pathsep.join([str(REPO)] + ([old] if old else []))
    try:
        doc = xacro.process_file(str(XACRO_FILE))
        return doc.toprettyxml(indent='  ') if pretty else doc.toxml()
    finally:
        if old is None:
            del os.environ['ROS_PACKAGE_PATH']
        else:
            os.environ['ROS_PACKAGE_PATH'] = old


@pytest.fixture(scope='session')
def racebot_xml():
    return render_racebot()

"""Shared fixtures of the unit tests: the racebot model rendered from its xacro, once per session.

The tests mirror racebot_sim_bridge's layout (one folder per subpackage; upstream_compat, tutorial, tools and
nodes for the rest). What several test modules share is in shared modules beside this file (fakes.py: the log,
rospy and controller I/O stand-ins; model_plugin_sim.py, sensors_sim.py, wheel_robot.py, ...: worlds and robots),
never imported from another test module; pytest.ini puts this folder on the path."""
import os

import pytest
from hypothesis import settings

from racebot_model import render_racebot

# The suite's property tests draw the same examples every run (derandomize): a failure is a defect found
# once and kept, never a run that fails one time in ten. To explore new examples, run pytest with
# HYPOTHESIS_PROFILE=explore; a failure found so goes in as an @example of its test.
settings.register_profile('suite', derandomize=True)
settings.register_profile('explore', derandomize=False)
settings.load_profile(os.environ.get('HYPOTHESIS_PROFILE', 'suite'))


@pytest.fixture(scope='session')
def racebot_xml():
    return render_racebot()

"""Where a user reads what racebot simulates: the README's table, named by every warning about a plugin,
sensor or controller type racebot does not have."""
import os

TITLE = 'Supported plugins, sensors and controllers'


def readme_path():
    """racebot's README.md in this source tree (this module is racebot_sim_bridge/src/racebot_sim_bridge/,
    three levels below it), or None where the package is installed without it."""
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.normpath(os.path.join(here, '..', '..', '..', 'README.md'))
    return path if os.path.isfile(path) else None


WHERE = "the table '%s' in %s" % (TITLE, readme_path() or "racebot's README.md")

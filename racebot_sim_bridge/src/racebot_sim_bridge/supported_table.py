"""Where a user reads what racebot simulates: the table in docs/SUPPORTED.md, named by every warning about a
plugin, sensor or controller type racebot does not have."""
import os

TITLE = 'Supported plugins, sensors and controllers'
PAGE = os.path.join('docs', 'SUPPORTED.md')


def page_path():
    """docs/SUPPORTED.md in this source tree (this module is racebot_sim_bridge/src/racebot_sim_bridge/, three
    levels below the repository root), or None where the package is installed without it."""
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.normpath(os.path.join(here, '..', '..', '..', PAGE))
    return path if os.path.isfile(path) else None


WHERE = "the table '%s' in %s" % (TITLE, page_path() or "racebot's %s" % PAGE)

"""The racebot model rendered from its xacro, as robot_description holds it (conftest's `racebot_xml` fixture
gives it once per session; a test that needs its own rendering calls render_racebot)."""
import os
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
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

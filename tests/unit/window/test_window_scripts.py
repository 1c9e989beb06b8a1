"""gazebo_ros's gzclient and gazebo scripts start their programs. The layout move once left them importing
main without calling it: `rosrun gazebo_ros gzclient` did nothing and exited 0, so racebot.launch opened
no 3D window and said nothing. No ROS master: gzclient --version ends before its node starts."""
import ast
import os
import subprocess
import sys
from pathlib import Path

from racebot_sim_bridge.window.gzclient import VERSION

REPO = Path(__file__).resolve().parents[3]
GAZEBO_ROS_SCRIPTS = REPO / 'upstream_compat' / 'gazebo_ros' / 'scripts'


def python_scripts():
    """Every Python executable in a scripts/ folder of the repository's packages."""
    for folder in sorted(REPO.glob('*/scripts')) + sorted(REPO.glob('upstream_compat/*/scripts')):
        for path in sorted(folder.iterdir()):
            if path.is_file() and path.read_text(errors='replace').startswith('#!/usr/bin/env python3'):
                yield path


def calls(tree):
    return {node.func.id for node in ast.walk(tree) if isinstance(node, ast.Call) and isinstance(node.func, ast.Name)}


def test_gzclient_runs():
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    result = subprocess.run([sys.executable, str(GAZEBO_ROS_SCRIPTS / 'gzclient'), '--version'], env=env,
                            capture_output=True, text=True, timeout=60)
    assert (result.returncode, result.stdout.strip()) == (0, VERSION), result.stderr


def test_every_script_that_imports_main_calls_it():
    scripts = list(python_scripts())
    assert GAZEBO_ROS_SCRIPTS / 'gazebo' in scripts
    for path in scripts:
        tree = ast.parse(path.read_text(), str(path))
        imported = {alias.asname or alias.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
                    for alias in node.names}
        if 'main' in imported:
            assert 'main' in calls(tree), '%s imports main and never calls it' % path.relative_to(REPO)

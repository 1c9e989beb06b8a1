"""racebot's node executables carry the tutorial's names, every launch, test and tool names them so, and a
script named like a module (`transform.py`) never imports itself in place of a package. No ROS master.

roslaunch and rosrun find a node by its file name in the package (`type="servo_commands.py"`,
`rosrun racebot_control servo_commands.py`); Python puts the script's own folder first on sys.path, so
a script whose name is a module that it, its node module or their imports load would shadow that module.
"""
import ast
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
# package -> the executables the tutorial's launch files and commands name (chapter 6)
TUTORIAL_SCRIPTS = {
    'racebot_control': {'servo_commands.py', 'transform.py'},
    'racebot_gazebo': {'keyboard_teleop.py'},
}
# package -> racebot's own executables beside them, beyond the chapter (the odometry nodes, gazebo_odometry.launch)
OWN_SCRIPTS = {'racebot_gazebo': {'gazebo_odometry', 'wheel_odometry'}}
EXCLUDED = {'build', 'devel', '.venv', 'install', 'out', '.git', 'node_modules'}
NODE_TAG = re.compile(r'<node\b[^>]*>', re.S)
ATTRIBUTE = re.compile(r'\b(pkg|type)\s*=\s*"([^"]*)"')
ROSRUN = re.compile(r"""['"]rosrun['"]\s*,\s*['"](\w+)['"]\s*,\s*['"]([\w.]+)['"]""")


def scripts_of(package):
    return sorted((REPO / package / 'scripts').iterdir())


def installed_programs(package):
    """The paths catkin_install_python(PROGRAMS ...) lists in the package's CMakeLists.txt."""
    text = (REPO / package / 'CMakeLists.txt').read_text()
    block = re.search(r'catkin_install_python\(\s*PROGRAMS(.*?)DESTINATION', text, re.S)
    assert block, '%s/CMakeLists.txt has no catkin_install_python(PROGRAMS ...)' % package
    return set(block.group(1).split())


def repository_files(suffixes):
    for root, dirs, files in os.walk(REPO):
        dirs[:] = sorted(d for d in dirs if d not in EXCLUDED)
        for name in sorted(files):
            if name.endswith(suffixes):
                yield Path(root) / name


def node_references():
    """(file, package, type) of every node of ours that a launch/test file or a Python file starts."""
    found = []
    for path in repository_files(('.launch', '.test', '.py', '.sh', '.md')):
        text = path.read_text(errors='replace')
        for tag in NODE_TAG.findall(text):
            attributes = dict(ATTRIBUTE.findall(tag))
            if attributes.get('pkg') in TUTORIAL_SCRIPTS and 'type' in attributes:
                found.append((path, attributes['pkg'], attributes['type']))
        for package, executable in ROSRUN.findall(text):
            if package in TUTORIAL_SCRIPTS:
                found.append((path, package, executable))
    return found


@pytest.mark.parametrize('package', sorted(TUTORIAL_SCRIPTS))
def test_tutorial_names_are_the_executables(package):
    names = {p.name for p in scripts_of(package)}
    assert names == TUTORIAL_SCRIPTS[package] | OWN_SCRIPTS.get(package, set()), (
        '%s/scripts holds %s; the tutorial names %s, and racebot adds %s' % (
            package, sorted(names), sorted(TUTORIAL_SCRIPTS[package]), sorted(OWN_SCRIPTS.get(package, ()))))
    for script in scripts_of(package):
        assert os.access(str(script), os.X_OK), '%s is not executable (chmod +x)' % script
    assert installed_programs(package) == {'scripts/' + n for n in names}, (
        '%s/CMakeLists.txt catkin_install_python does not list exactly its scripts' % package)


def test_every_reference_names_an_existing_executable():
    references = node_references()
    # the package's own launch files and the tests must be among what was read
    assert any(path.name == 'racebot_control.launch' for path, _, _ in references)
    assert any(path.name == 'racebot_launch_test.py' for path, _, _ in references)
    wrong = ['%s: %s %s' % (path.relative_to(REPO), package, executable)
             for path, package, executable in references
             if executable not in TUTORIAL_SCRIPTS[package] | OWN_SCRIPTS.get(package, set())]
    assert not wrong, 'these name executables that do not exist (the tutorial\'s names end in .py):\n' + \
        '\n'.join(wrong)


def imported_top_levels(path):
    """Top-level module names a Python file imports, at module level or inside functions."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            names.update(alias.name.split('.')[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split('.')[0])
    return names


@pytest.mark.parametrize('package', sorted(TUTORIAL_SCRIPTS))
def test_no_script_is_named_like_a_module_its_node_imports(package):
    stems = {p.stem for p in scripts_of(package)}
    sources = scripts_of(package) + sorted((REPO / package / 'src' / package).glob('*.py'))
    for source in sources:
        clash = stems & imported_top_levels(source)
        assert not clash, ('%s imports %s, which the script %s in %s/scripts would shadow (Python puts the '
                           'script folder first on sys.path): rename the script'
                           % (source.relative_to(REPO), sorted(clash), sorted(clash), package))


LOADED_FROM = r'''
import importlib, runpy, sys
script, folders = sys.argv[1], sys.argv[2:]
sys.path[0] = folders[0]           # as when the script is run: its own folder first
sys.path[1:1] = folders[1:]        # catkin's relay folder (devel/lib/<package>) next
tree = __import__('ast').parse(open(script).read())
for node in __import__('ast').walk(tree):   # the script's own imports, without calling main()
    if isinstance(node, __import__('ast').ImportFrom) and node.module:
        importlib.import_module(node.module)
for name in ('rospy', 'ackermann_msgs.msg', 'geometry_msgs.msg', 'std_msgs.msg', 'tkinter'):
    importlib.import_module(name)   # what the nodes import lazily inside main()
for name, module in sorted(sys.modules.items()):
    path = getattr(module, '__file__', None) or ''
    if any(path.startswith(f + '/') for f in folders):
        print(name, path)
'''


@pytest.mark.parametrize('script', [p for package in sorted(TUTORIAL_SCRIPTS) for p in scripts_of(package)],
                         ids=lambda p: p.name)
def test_running_a_script_loads_no_module_from_its_folder(script):
    """The script's imports, with sys.path as a run of it (from scripts/ or catkin's devel relay) sets it."""
    package = script.parent.parent.name
    folders = [str(script.parent)]
    relay_folder = REPO / 'devel' / 'lib' / package
    if relay_folder.is_dir():
        folders.append(str(relay_folder))
    env = dict(os.environ)
    env['PYTHONPATH'] = os.pathsep.join([str(REPO / package / 'src')]
                                        + [p for p in env.get('PYTHONPATH', '').split(os.pathsep) if p])
    done = subprocess.run([sys.executable, '-c', LOADED_FROM, str(script)] + folders, env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout == '', 'modules loaded from the script folders (self-import):\n' + done.stdout

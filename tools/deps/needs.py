"""What a workspace or a package needs: the dependencies its package.xml files declare (read by catkin_pkg, with
REP 149 conditions evaluated for ROS 1 on Python 3) and the packages its launch files name (`<node pkg=...>`,
`<test pkg=...>`, `$(find pkg)` anywhere, and the package of a pluginlib lookup name given as a `<param>` or `<arg>`
value). Pure: reads files, runs nothing.
"""
import os
import re
import xml.etree.ElementTree as ElementTree

from catkin_pkg.packages import find_packages

# The values REP 149 conditions (`condition="$ROS_VERSION == 1"`) are evaluated against.
CONDITIONS = {'ROS_VERSION': '1', 'ROS_PYTHON_VERSION': '3', 'ROS_DISTRO': 'noetic'}
FIND = re.compile(r'\$\(find\s+([A-Za-z][A-Za-z0-9_]*)\)')
PKG_NAME = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')
# a pluginlib lookup name, 'package/ClassName' (move_base's base_local_planner:=dwa_local_planner/DWAPlannerROS):
# the plugin's package is needed although no <node> names it
PLUGIN_LOOKUP = re.compile(r'^([a-z][a-z0-9_]*)/[A-Z][A-Za-z0-9_]*$')
LAUNCH_SUFFIXES = ('.launch', '.launch.xml')
SKIPPED_DIRS = {'.git', 'build', 'devel', 'build_isolated', 'devel_isolated', 'install', 'node_modules'}

# racebot's stand-ins (upstream_compat/) that are reduced Python copies of an upstream package which builds on
# Debian: for these, the real package is fetched and built in the underlay, where it comes first on every path
# and so shadows ours. Every other stand-in (gazebo_ros, the ros_control and ros_controllers names, the message
# packages) counts as provided: the real one needs Gazebo or C++ racebot does not have, or racebot's is complete.
GIVE_WAY = ('interactive_marker_twist_server', 'rgbd_launch', 'twist_mux')


def local_packages(path):
    """{package name: (its folder, catkin_pkg Package)} for every package.xml at or below `path`, as catkin
    finds them (CATKIN_IGNORE and nested package.xml rules included)."""
    found = {}
    for rel, package in find_packages(path).items():
        package.evaluate_conditions(CONDITIONS)
        found[package.name] = (os.path.normpath(os.path.join(path, rel)), package)
    return found


def declared(package, tests=True):
    """The names a parsed package.xml depends on (build, buildtool, export, exec; test ones when `tests`)."""
    groups = [package.build_depends, package.buildtool_depends, package.build_export_depends,
              package.buildtool_export_depends, package.exec_depends]
    if tests:
        groups.append(package.test_depends)
    return {dep.name for group in groups for dep in group if dep.evaluated_condition is not False}


def launch_files(folder):
    """The launch files below a package folder, relative paths, sorted."""
    found = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith('.'))
        if 'CATKIN_IGNORE' in files and root != folder:
            dirs[:] = []
            continue
        found += [os.path.relpath(os.path.join(root, f), folder) for f in files if f.endswith(LAUNCH_SUFFIXES)]
    return sorted(found)


def launch_names(text):
    """The package names a launch file's text uses: `pkg` of <node> and <test> (when not an `$(arg ...)`), every
    `$(find pkg)`, and the package of a `<param value>` or `<arg value|default>` that is a pluginlib lookup name.
    Comments name nothing; a file that is not well-formed XML still gives every `$(find pkg)` of its text."""
    try:
        root = ElementTree.fromstring(text)
    except ElementTree.ParseError:
        return set(FIND.findall(text))
    names = set()  # from attributes and text only: a commented-out <include> needs nothing
    for element in root.iter():
        for value in list(element.attrib.values()) + [element.text or '', element.tail or '']:
            names.update(FIND.findall(value))
        if element.tag in ('node', 'test') and PKG_NAME.match(element.get('pkg', '')):
            names.add(element.get('pkg'))
        if element.tag in ('param', 'arg'):
            for value in (element.get('value'), element.get('default')):
                plugin = PLUGIN_LOOKUP.match((value or '').strip())
                if plugin:
                    names.add(plugin.group(1))
    return names


def package_needs(folder, package, tests=True):
    """{name: [why]} for one package: its declared dependencies ('package.xml') and its launch files' names
    ('launch/x.launch')."""
    needs = {name: ['package.xml'] for name in declared(package, tests)}
    for rel in launch_files(folder):
        with open(os.path.join(folder, rel), errors='replace') as f:
            for name in launch_names(f.read()):
                needs.setdefault(name, []).append(rel)
    needs.pop(package.name, None)
    return needs


def needs_of(packages, tests=True):
    """{name: {needing package, ...}} over `packages` ({name: (folder, Package)}), leaving out the packages'
    own names."""
    needs = {}
    for name, (folder, package) in sorted(packages.items()):
        for need in package_needs(folder, package, tests):
            if need not in packages:
                needs.setdefault(need, set()).add(name)
    return needs

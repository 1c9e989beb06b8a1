"""A small ROS 1 world for make deps with no network (helpers of deps_underlay_test.py and of the unit tests in
tests/unit/tools/test_deps.py, not a test node itself).

make_world(root) writes, under `root`:
  mirrors/racebot-fixture+<repo>/repo   git repositories of our own, tagged at their release, laid out as make
                                        corpus's mirrors (ROOT/<owner>+<name>/repo)
  rosdistro/                            index-v4.yaml, noetic/distribution.yaml releasing those repositories
                                        (source URLs on github.com, which the test never reaches), rosdep/base.yaml
                                        with one key for Debian bookworm
  target/my_robot                       a package that needs them: probe_core and the rosdep key in its package.xml,
                                        probe_tools and no_such_pkg in its launch file, probe_needs_broken too
The repositories: probe_core (a C++ executable and a header; beside it probe_unused, which does not compile and
nothing needs), probe_tools (a Python script; needs probe_core; its mirror lacks the release's tag, which its
release repository's mirror, racebot-fixture+probe_tools-release, has), probe_broken (probe_broken does not compile;
probe_needs_broken needs it).
"""
import os
import subprocess

OWNER = 'racebot-fixture'
SYSDEP_KEY = 'racebot_fixture_sysdep'
# an installed Debian package racebot needs anyway (tools/debian-packages.txt)
SYSDEP_DEBIAN = 'python3-rospkg'


def package_xml(name, depends=(), exec_depends=()):
    lines = ['<?xml version="1.0"?>', '<package format="3">', '  <name>%s</name>' % name,
             '  <version>0.1.0</version>', '  <description>%s: a make deps test fixture</description>' % name,
             '  <maintainer email="racebot@example.com">racebot</maintainer>', '  <license>BSD</license>',
             '  <buildtool_depend>catkin</buildtool_depend>']
    lines += ['  <depend>%s</depend>' % d for d in depends]
    lines += ['  <exec_depend>%s</exec_depend>' % d for d in exec_depends]
    return '\n'.join(lines + ['</package>', ''])


def cpp_package(name, source, depends=()):
    """{relative path: text} of a C++ catkin package with one executable built from `source`."""
    components = ' '.join(depends)
    return {
        'package.xml': package_xml(name, depends),
        'CMakeLists.txt': 'cmake_minimum_required(VERSION 3.0.2)\nproject(%s)\n'
                          'find_package(catkin REQUIRED %s)\n'
                          'catkin_package(INCLUDE_DIRS include)\n'
                          'include_directories(include ${catkin_INCLUDE_DIRS})\n'
                          'add_executable(%s_hello src/hello.cpp)\n'
                          'install(TARGETS %s_hello RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})\n'
                          % (name, ('COMPONENTS ' + components) if components else '', name, name),
        'include/%s/probe.h' % name: '#pragma once\nnamespace %s { inline int answer() { return 42; } }\n' % name,
        'src/hello.cpp': source,
    }


GOOD_CPP = '#include <iostream>\n#include "probe_core/probe.h"\nint main() { std::cout << "probe_core " ' \
           '<< probe_core::answer() << std::endl; return 0; }\n'
BROKEN_CPP = '#include <iostream>\nint main() {\n  return undeclared_name;\n}\n'

REPOS = {
    'probe_core': ('0.1.0', {
        'probe_core': cpp_package('probe_core', GOOD_CPP),
        'probe_unused': cpp_package('probe_unused', BROKEN_CPP),
    }),
    'probe_tools': ('0.2.0', {
        '.': {
            'package.xml': package_xml('probe_tools', exec_depends=['probe_core']),
            'CMakeLists.txt': 'cmake_minimum_required(VERSION 3.0.2)\nproject(probe_tools)\n'
                              'find_package(catkin REQUIRED)\ncatkin_package()\n'
                              'catkin_install_python(PROGRAMS scripts/probe_tool '
                              'DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})\n',
            'scripts/probe_tool': '#!/usr/bin/env python3\nprint("probe_tools says hello")\n',
        },
    }),
    'probe_broken': ('1.0.0', {
        'probe_broken': cpp_package('probe_broken', BROKEN_CPP),
        'probe_needs_broken': cpp_package('probe_needs_broken', GOOD_CPP.replace('probe_core', 'probe_needs_broken'),
                                          depends=['probe_broken']),
    }),
}

TARGET_LAUNCH = '''<launch>
  <arg name="extra" default="$(find probe_core)/include"/>
  <node pkg="probe_tools" type="probe_tool" name="probe_tool"/>
  <node pkg="no_such_pkg" type="nothing" name="nothing"/>
  <node pkg="$(arg extra)" type="skipped" name="skipped"/>
</launch>
'''


def write_files(root, files):
    for rel, text in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w') as f:
            f.write(text)
        if rel.startswith('scripts/'):
            os.chmod(path, 0o755)


def git_repo(path, packages, tag):
    """A git repository at `path` holding `packages` ({folder in the repo: files}), tagged `tag`."""
    for folder, files in packages.items():
        write_files(os.path.join(path, folder), files)
    env = dict(os.environ, GIT_AUTHOR_NAME='racebot', GIT_AUTHOR_EMAIL='racebot@example.com',
               GIT_COMMITTER_NAME='racebot', GIT_COMMITTER_EMAIL='racebot@example.com')
    for args in (['init', '-q', '-b', 'main'], ['add', '-A'], ['commit', '-q', '-m', 'release ' + tag],
                 ['tag', tag]):
        subprocess.run(['git'] + args, cwd=path, env=env, check=True, stdout=subprocess.DEVNULL)


def distribution_yaml(repos):
    lines = ['%YAML 1.1', '---', 'release_platforms:', '  debian: [buster]', '  ubuntu: [focal]', 'repositories:']
    for name, (version, packages) in sorted(repos.items()):
        names = sorted(name if folder == '.' else folder for folder in packages)
        lines += ['  %s:' % name, '    release:', '      packages: [%s]' % ', '.join(names),
                  "      tags: {release: 'release/noetic/{package}/{version}'}",
                  '      url: https://github.com/%s/%s-release.git' % (OWNER, name),
                  '      version: %s-1' % version, '    source:', '      type: git',
                  '      url: https://github.com/%s/%s.git' % (OWNER, name), '      version: main',
                  '    status: maintained']
    return '\n'.join(lines + ['type: distribution', 'version: 2', ''])


INDEX = '''%YAML 1.1
---
distributions:
  noetic:
    distribution: [noetic/distribution.yaml]
    distribution_status: end-of-life
    distribution_type: ros1
    python_version: 3
type: index
version: 4
'''


# A source repository whose mirror is older than its release (robot_localization's mirror stops at 2.7.5, the
# release is 2.7.7): its tag is missing, and the release repository's copy has the release's tag.
STALE = {'probe_tools': '0.1.9'}


def make_world(root):
    """{'mirrors', 'rosdistro', 'target'}: the folders written under `root` (see the module's docstring)."""
    mirrors = os.path.join(root, 'mirrors')
    for name, (version, packages) in REPOS.items():
        git_repo(os.path.join(mirrors, '%s+%s' % (OWNER, name), 'repo'), packages, STALE.get(name, version))
        if name in STALE:  # bloom's release repository: the package at the root of its release tag (one package)
            (folder, files), = packages.items()
            git_repo(os.path.join(mirrors, '%s+%s-release' % (OWNER, name), 'repo'), {'.': files},
                     'release/noetic/%s/%s-1' % (name if folder == '.' else folder, version))
    rosdistro = os.path.join(root, 'rosdistro')
    write_files(rosdistro, {'index-v4.yaml': INDEX, 'noetic/distribution.yaml': distribution_yaml(REPOS),
                            'rosdep/base.yaml': '%s:\n  debian: [%s]\n' % (SYSDEP_KEY, SYSDEP_DEBIAN)})
    target = os.path.join(root, 'target', 'my_robot')
    write_files(target, {'package.xml': package_xml('my_robot', ['std_msgs', 'probe_core', 'probe_needs_broken'],
                                                    [SYSDEP_KEY]),
                         'CMakeLists.txt': 'cmake_minimum_required(VERSION 3.0.2)\nproject(my_robot)\n'
                                           'find_package(catkin REQUIRED)\ncatkin_package()\n',
                         'launch/robot.launch': TARGET_LAUNCH})
    return {'mirrors': mirrors, 'rosdistro': rosdistro, 'target': target}

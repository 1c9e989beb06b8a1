#!/usr/bin/env python3
"""make deps builds what a package needs from a local folder of sources, with no network (issue 38, items 2 and 5).

deps_fixture.py writes git repositories of our own laid out as mirrors, a rosdistro whose noetic distribution
releases them (their URLs are on github.com, which must never be reached: the repositories do not exist there) and
a target package, my_robot, whose package.xml and launch file need them. tools/deps/run.py runs as `make deps`
runs it, with a cache of its own. Checked: the packages nobody provides are built in the underlay at their release
tags (probe_core through package.xml and `$(find ...)`, probe_tools through `<node pkg=...>` and from its
release repository, its source mirror lacking the release's tag, probe_core's
neighbour probe_unused, which does not compile, left alone); the underlay's setup.bash gives them and racebot
together; a package that does not compile, the package that needs it and a name released nowhere each get one line
saying why; the rosdep key of the local rosdistro resolves to its Debian package. Then the second run: it builds
nothing (no new build log) and says so, in seconds.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

import rostest

import deps_fixture

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
TOOL = os.path.join(REPO, 'tools', 'deps', 'run.py')
FIRST_RUN_TIMEOUT = 360.0   # wall s: rosdep update and catkin_make_isolated of four tiny packages on a busy machine
CACHED_RUN_LIMIT = 20.0     # wall s for the second run, which only reads its record (about 1 s when idle)


class DepsUnderlayTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.root = tempfile.mkdtemp(prefix='racebot_deps_', dir='/tmp')
        cls.world = deps_fixture.make_world(cls.root)
        cls.cache = os.path.join(cls.root, 'cache')
        cls.first, cls.first_seconds = cls.run_tool()
        cls.logs = sorted(os.listdir(os.path.join(cls.cache, 'ws', 'logs')))
        cls.second, cls.second_seconds = cls.run_tool()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.root, ignore_errors=True)

    @classmethod
    def run_tool(cls):
        env = {k: v for k, v in os.environ.items() if k not in ('ROSDISTRO_INDEX_URL', 'RACEBOT_CORPUS_DIR')}
        env['RACEBOT_DEPS_CACHE'] = cls.cache
        cmd = [sys.executable, TOOL, '--mirrors', cls.world['mirrors'], '--rosdistro', cls.world['rosdistro'],
               '--no-install', cls.world['target']]
        started = time.time()
        done = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=FIRST_RUN_TIMEOUT)
        return done, time.time() - started

    def lines(self, done, first_word):
        return [line.strip() for line in done.stdout.splitlines() if line.strip().startswith(first_word + ' ')]

    def in_underlay(self, command):
        script = 'source %s && %s' % (os.path.join(self.cache, 'ws', 'devel_isolated', 'setup.bash'), command)
        return subprocess.run(['bash', '-c', script], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=60)

    def test_what_nobody_provides_is_built_at_its_release(self):
        # probe_tools's mirror lacks its release tag 0.2.0: it comes from its release repository's tag of 0.2.0
        self.assertEqual(sorted(self.lines(self.first, 'built')),
                         ['built    probe_core (probe_core)',
                          'built    probe_tools (probe_tools-release/probe_tools)'], self.first.stdout)
        self.assertIn('from source: probe_broken 1.0.0, probe_core 0.1.0, probe_tools-release/probe_tools '
                      'release/noetic/probe_tools/0.2.0-1', self.first.stdout)
        tag = subprocess.run(['git', 'describe', '--tags', '--exact-match'], cwd=os.path.join(
            self.cache, 'ws', 'src', 'probe_core'), stdout=subprocess.PIPE, text=True).stdout.strip()
        self.assertEqual(tag, '0.1.0')

    def test_the_underlay_gives_the_built_packages_on_top_of_racebot(self):
        done = self.in_underlay('rosrun probe_core probe_core_hello && rosrun probe_tools probe_tool && '
                                'rospack find racebot_sim_bridge')
        self.assertEqual(done.returncode, 0, done.stdout)
        self.assertEqual(done.stdout.splitlines()[:2], ['probe_core 42', 'probe_tools says hello'])
        self.assertEqual(done.stdout.splitlines()[2], os.path.join(REPO, 'racebot_sim_bridge'))

    def test_a_package_nothing_needs_is_not_built(self):
        self.assertNotIn('probe_unused', self.first.stdout)
        self.assertFalse(os.path.exists(os.path.join(self.cache, 'ws', 'build_isolated', 'probe_unused')))

    def test_each_failure_is_one_line_naming_the_package_and_why(self):
        self.assertEqual(self.first.returncode, 1, self.first.stdout)
        failed = self.lines(self.first, 'failed')
        self.assertEqual(len(failed), 1, self.first.stdout)
        want = r'^failed +probe_broken \(probe_broken\): src/hello.cpp:3: error: .*undeclared_name'
        if not re.search(want, failed[0]):
            logs = os.path.join(self.cache, 'ws', 'logs')
            with open(os.path.join(logs, sorted(os.listdir(logs))[0]), errors='replace') as f:
                self.fail('%r is not the compiler\'s error; the build log:\n%s' % (failed[0], f.read()[-6000:]))
        self.assertEqual(self.lines(self.first, 'skipped'),
                         ['skipped  probe_needs_broken (probe_broken): needs probe_broken, which failed to build'])
        self.assertEqual(self.lines(self.first, 'unknown'),
                         ['unknown  no_such_pkg (needed by my_robot): no rosdep rule for debian:bookworm and no Noetic '
                          'release in the rosdistro'])

    def test_the_local_rosdistros_rosdep_key_resolves_to_debian(self):
        self.assertRegex(self.first.stdout, r'needed name\(s\): 0 racebot, \d+ installed, 1 Debian via rosdep')

    def test_the_second_run_builds_nothing_in_seconds(self):
        self.assertIn('cached, nothing to do', self.second.stdout)
        self.assertEqual(sorted(os.listdir(os.path.join(self.cache, 'ws', 'logs'))), self.logs)
        self.assertLess(self.second_seconds, CACHED_RUN_LIMIT)
        self.assertEqual(self.lines(self.second, 'built'), self.lines(self.first, 'built'))
        self.assertEqual(self.lines(self.second, 'failed'), self.lines(self.first, 'failed'))


if __name__ == '__main__':
    rostest.rosrun('racebot_tests', 'deps_underlay', DepsUnderlayTest, sys.argv)

"""A user's catkin workspace under /tmp, overlaying racebot's devel space, and roslaunch started in it from
a shell, as a user starts it (helpers of the rostest nodes in this folder, not a test node itself)."""
import os
import re
import shutil
import signal
import subprocess
import tempfile
import time

import rospy

BUILD_TIMEOUT = 240.0  # wall s for catkin_make of a few tiny packages on a busy 2-core machine
STOP_TIMEOUT = 30.0    # wall s roslaunch gets to stop its nodes after SIGINT


def user_environment():
    """What a user's terminal has before sourcing anything: no ROS or racebot variables. The login shell
    (`bash -l`) then reads the profile files as a terminal does. ROS_MASTER_URI is this test's master,
    ROS_HOSTNAME loopback (as tools/run_tests.py sets for the whole suite)."""
    env = {name: os.environ[name] for name in ('HOME', 'USER', 'LOGNAME', 'LANG', 'TERM') if name in os.environ}
    env['PATH'] = '/usr/local/bin:/usr/bin:/bin'
    env['ROS_MASTER_URI'] = os.environ['ROS_MASTER_URI']
    env['ROS_HOSTNAME'] = 'localhost'
    return env


def in_user_shell(setup, command, timeout):
    """(exit code, output) of `command` in a user's login shell (user_environment) that sourced `setup`; the exit
    code is 'timed out after N s' when it did not end in `timeout` wall s."""
    try:
        done = subprocess.run(['bash', '-lc', 'source %s && %s' % (setup, command)], env=user_environment(),
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
    except subprocess.TimeoutExpired as timed_out:
        return 'timed out after %.0f s' % timeout, (timed_out.output or b'').decode(errors='replace')
    return done.returncode, done.stdout.decode(errors='replace')


class Workspace:
    """A catkin workspace in a fresh folder under /tmp: `src/` holds the given packages, `catkin_make`
    builds it on top of whatever workspace the calling environment has sourced (racebot's devel)."""

    def __init__(self, prefix):
        self.root = tempfile.mkdtemp(prefix=prefix, dir='/tmp')
        self.src = os.path.join(self.root, 'src')
        os.mkdir(self.src)
        self.setup = os.path.join(self.root, 'devel', 'setup.bash')

    def copy_packages(self, folder):
        """Copies every package folder in `folder` into src/ (a fixture workspace's packages)."""
        for package in sorted(os.listdir(folder)):
            shutil.copytree(os.path.join(folder, package), os.path.join(self.src, package))

    def link(self, package_dir):
        """Puts an existing package folder into src/ as a link (catkin follows it)."""
        os.symlink(package_dir, os.path.join(self.src, os.path.basename(package_dir)))

    def write(self, relative, text, executable=False):
        path = os.path.join(self.src, relative)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w') as f:
            f.write(text)
        if executable:
            os.chmod(path, 0o755)
        return path

    def build(self, env=None):
        """catkin_make; AssertionError with the end of its output when it fails."""
        log = os.path.join(self.root, 'catkin_make.log')
        with open(log, 'w') as out:
            code = subprocess.call(['catkin_make', '-C', self.root], stdout=out, stderr=subprocess.STDOUT,
                                   env=env, timeout=BUILD_TIMEOUT)
        if code != 0:
            with open(log) as f:
                raise AssertionError('catkin_make in %s failed (%d):\n%s' % (self.root, code, f.read()[-3000:]))
        return self.setup

    def remove(self):
        shutil.rmtree(self.root, ignore_errors=True)


class ShellCommand:
    """`bash -c` (or `bash -lc`, a login shell) running `command` in a session of its own, output in a log
    file; stop() ends it and every process it started, as Ctrl-C in that terminal would."""

    def __init__(self, command, env, log_path, login=False):
        self.log_path = log_path
        self._log = open(log_path, 'w')
        # A terminal shows roslaunch's lines as they come (line-buffered); into a file Python would hold
        # them in an 8 kB buffer, and a line the test waits for (a node's "process has finished cleanly")
        # could sit there until more output pushed it out (a fresh-root CI run timed out on it so).
        env = dict(env, PYTHONUNBUFFERED='1')
        self.process = subprocess.Popen(['bash', '-lc' if login else '-c', command], env=env,
                                        stdout=self._log, stderr=subprocess.STDOUT, start_new_session=True)

    def output(self):
        with open(self.log_path, errors='replace') as f:
            return f.read()

    def running(self):
        return self.process.poll() is None

    def stop(self):
        """SIGINT to the whole group (roslaunch stops its nodes), SIGKILL what is left after STOP_TIMEOUT."""
        if self.running():
            os.killpg(self.process.pid, signal.SIGINT)
            try:
                self.process.wait(STOP_TIMEOUT)
            except subprocess.TimeoutExpired:
                pass
        try:
            os.killpg(self.process.pid, signal.SIGKILL)  # nodes that outlived roslaunch, if any
        except ProcessLookupError:
            pass
        self.process.wait()
        self._log.close()



FIXTURE_ROBOTS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'fixtures', 'robots')


def fixture_launch(args, name):
    """`roslaunch ARGS` in a shell with the fixture robot packages (tests/fixtures/robots) on ROS_PACKAGE_PATH,
    its output in a log under ROS_LOG_DIR named after `name`; returns (ShellCommand, LaunchWatch)."""
    env = dict(os.environ, ROS_PACKAGE_PATH=FIXTURE_ROBOTS + os.pathsep + os.environ['ROS_PACKAGE_PATH'])
    log_dir = os.environ.get('ROS_LOG_DIR', '/tmp')
    os.makedirs(log_dir, exist_ok=True)
    handle, log = tempfile.mkstemp(prefix='%s_roslaunch-' % name, suffix='.log', dir=log_dir)
    os.close(handle)
    shell = ShellCommand('exec roslaunch %s' % args, env, log)
    return shell, LaunchWatch(shell)


class LaunchWatch:
    """Waits on conditions while a ShellCommand runs roslaunch. A wait fails at once, with roslaunch's
    output, when roslaunch has ended or one of its nodes died; after one wait failed, later waits fail at
    once (each would otherwise sit out its whole timeout on a launch that is already broken)."""

    DIED = re.compile(r'\[([\w/.-]+)\] process has died')

    def __init__(self, shell):
        self.shell = shell
        self.broken = None

    def wait(self, condition, what, timeout, period=0.05):
        if self.broken:
            raise AssertionError('not waiting for %s: %s' % (what, self.broken))
        deadline = time.time() + timeout
        while True:
            output = self.shell.output()
            died = self.DIED.search(output)
            if not self.shell.running() or died:
                self._fail('roslaunch ended (%s)' % self.shell.process.returncode if not died
                           else 'node %s died' % died.group(1), what, output)
            value = condition()
            if value:
                return value
            if time.time() > deadline or rospy.is_shutdown():
                self._fail('timed out after %.0f s (wall)' % timeout, what, output)
            time.sleep(period)

    def _fail(self, why, what, output):
        self.broken = '%s while waiting for %s' % (why, what)
        raise AssertionError('%s; roslaunch\'s output ends:\n%s' % (self.broken, output[-3000:]))

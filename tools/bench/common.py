"""What every part of the bench shares: paths, worlds, /proc readings, launches on private masters
(statistics are in stats.py). No rospy at import time (the in-process parts run without it)."""
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ROOM_WORLD = os.path.join(REPO, 'racebot_gazebo', 'worlds', 'room_mini.world')
EMPTY_WORLD = os.path.join(REPO, 'racebot_sim_bridge', 'worlds', 'empty.world')
XACRO_FILE = os.path.join(REPO, 'racebot_description', 'urdf', 'ackermann', 'racecar.xacro')
CONTROL_YAML = os.path.join(REPO, 'racebot_control', 'config', 'racebot_control.yaml')
CONTROLLERS = ('left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
               'left_front_wheel_velocity_controller', 'right_front_wheel_velocity_controller',
               'left_steering_hinge_position_controller', 'right_steering_hinge_position_controller',
               'joint_state_controller')
NAMESPACE = '/racebot'
REAR_AXLE_X = -0.13  # m, rear axle middle in the model frame (base_footprint); racecar.xacro
WHEELBASE = 0.26     # m, rear axle to the steering hinges; racecar.xacro

# The bench's own launch of the simulator under test: empty_world.launch (ours) with the room or
# empty world, the car spawned, the seven controllers by the spawner (joint_states at 50 Hz), and
# servo_commands when asked. Written under the output folder at run time (tools/ is no ROS package).
BRIDGE_LAUNCH = """<?xml version="1.0"?>
<!-- written by tools/run_bench.py: the simulator under test, as racebot.launch starts it minus
     robot_state_publisher, transform and the keyboard (the bench drives and reads the car itself) -->
<launch>
  <arg name="world_name"/>
  <arg name="servo" default="false"/>
  <arg name="steering_mode" default="parallel"/>
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="world_name" value="$(arg world_name)"/>
    <arg name="gui" value="false"/>
    <arg name="output" value="log"/>
  </include>
  <param name="robot_description"
         command="$(find xacro)/xacro '$(find racebot_description)/urdf/ackermann/racecar.xacro'"/>
  <node name="urdf_spawner" pkg="gazebo_ros" type="spawn_model"
        args="-urdf -model racebot -param robot_description -x 0 -y 0 -z 0"/>
  <rosparam file="$(find racebot_control)/config/racebot_control.yaml" command="load"/>
  <node name="controller_manager" pkg="controller_manager" type="spawner" ns="/racebot"
        args="%s"/>
  <node if="$(arg servo)" pkg="racebot_control" type="servo_commands.py" name="servo_commands">
    <param name="steering_mode" value="$(arg steering_mode)"/>
  </node>
</launch>
""" % ' '.join(CONTROLLERS)


class BenchError(RuntimeError):
    """A measurement could not be made; the message says which and why."""


def loadavg():
    return [round(x, 2) for x in os.getloadavg()]


# -- processes ------------------------------------------------------------------------------------
CLOCK_TICKS = os.sysconf('SC_CLK_TCK')


def cpu_seconds(pid):
    """User + system CPU time of a process so far, from /proc/<pid>/stat."""
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / float(CLOCK_TICKS)  # utime, stime (fields 14, 15)


def child_pids(pid):
    """The pids of a process's children (the world server's render worker), from /proc."""
    children = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open('/proc/%s/stat' % entry) as f:
                if int(f.read().rsplit(')', 1)[1].split()[1]) == pid:
                    children.append(int(entry))
        except (OSError, ValueError, IndexError):
            continue
    return children


def rss_bytes(pid):
    with open('/proc/%d/status' % pid) as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) * 1024
    raise BenchError('no VmRSS for process %d' % pid)


def steps_per_second(run_steps, wall_seconds, chunk=200):
    """Calls run_steps(chunk) for about wall_seconds (whole chunks); returns steps per wall second: the
    measuring loop of the bare-PyBullet ceilings (ceiling.py, fleet.py)."""
    start = time.perf_counter()
    n = 0
    while True:
        run_steps(chunk)
        n += chunk
        now = time.perf_counter()
        if now - start >= wall_seconds:
            return n / (now - start)


def free_port():
    s = socket.socket()
    s.bind(('localhost', 0))
    port = s.getsockname()[1]
    s.close()
    return port


def ros_env(port):
    env = dict(os.environ)
    env['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    env.setdefault('ROS_LOG_DIR', os.path.join(REPO, 'out', 'ros_log'))
    return env


class Process:
    """A child process in its own process group (so that stopping it stops what it started, and
    nothing else); output to a log file."""

    def __init__(self, cmd, log_path, env):
        self.cmd = cmd
        self.log_path = log_path
        self._log = open(log_path, 'w')
        self.started = time.monotonic()
        self.proc = subprocess.Popen(cmd, stdout=self._log, stderr=subprocess.STDOUT, env=env,
                                     start_new_session=True, cwd=REPO)

    def alive(self):
        return self.proc.poll() is None

    def stop(self, timeout=20.0):
        """SIGINT to the group (roslaunch shuts its nodes down), then SIGKILL to what is left."""
        if self.alive():
            try:
                os.killpg(self.proc.pid, signal.SIGINT)
            except ProcessLookupError:
                pass
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                pass
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)  # stragglers of this group only
        except ProcessLookupError:
            pass
        try:
            self.proc.wait(5)
        except subprocess.TimeoutExpired:
            pass
        self._log.close()

    def tail(self, n=30):
        try:
            with open(self.log_path) as f:
                return ''.join(f.readlines()[-n:])
        except OSError:
            return ''


def roslaunch(args, port, log_path):
    """`roslaunch -p PORT ARGS...`: starts its own master on PORT when none runs there."""
    return Process(['roslaunch', '-p', str(port)] + list(args), log_path, ros_env(port))


def roscore(port, log_path):
    proc = Process(['roscore', '-p', str(port)], log_path, ros_env(port))
    wait_for(lambda: master_online(port), 30, 'the ROS master on port %d' % port, proc)
    return proc


def master_online(port):
    import rosgraph
    try:
        return rosgraph.Master('/racebot_bench', master_uri='http://localhost:%d' % port).is_online()
    except Exception:  # not up yet
        return False


def wait_for(predicate, timeout, what, proc=None, period=0.05):
    """Polls predicate() until it is true; BenchError after timeout wall seconds (with the log tail
    of proc, if given, so the cause is visible)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        value = predicate()
        if value:
            return value
        if proc is not None and not proc.alive():
            raise BenchError('%s: the process exited (%s) before it was ready; last lines of %s:\n%s'
                             % (what, proc.proc.returncode, proc.log_path, proc.tail()))
        time.sleep(period)
    raise BenchError('%s not ready after %g s%s' % (what, timeout, (
        '; last lines of %s:\n%s' % (proc.log_path, proc.tail())) if proc is not None else ''))


# -- worlds and the model -------------------------------------------------------------------------
def fast_world(source, target):
    """A copy of an SDF world with real_time_update_rate 0 (as fast as possible)."""
    with open(source) as f:
        text = f.read()
    text, n = re.subn(r'<real_time_update_rate>[^<]*</real_time_update_rate>',
                      '<real_time_update_rate>0</real_time_update_rate>', text)
    if n != 1:
        raise BenchError('%s: expected one <real_time_update_rate>, found %d' % (source, n))
    with open(target, 'w') as f:
        f.write(text)
    return target


def render_racebot():
    """robot_description as the launch files make it (xacro, pretty-printed)."""
    import xacro
    old = os.environ.get('ROS_PACKAGE_PATH')
    if not old or REPO not in old.split(os.pathsep):
        os.environ['ROS_PACKAGE_PATH'] = os.pathsep.join([REPO] + ([old] if old else []))
    try:
        return xacro.process_file(XACRO_FILE).toprettyxml(indent='  ')
    finally:
        if old is None:
            os.environ.pop('ROS_PACKAGE_PATH', None)
        else:
            os.environ['ROS_PACKAGE_PATH'] = old


def controller_params():
    import yaml
    with open(CONTROL_YAML) as f:
        return yaml.safe_load(f)['racebot']


def write_bridge_launch(out_dir):
    path = os.path.join(out_dir, 'bridge.launch')
    with open(path, 'w') as f:
        f.write(BRIDGE_LAUNCH)
    return path


def python():
    return sys.executable


class quiet_stdout:
    """Silences file descriptor 1 (PyBullet's URDF loader prints every merged link there)."""

    def __enter__(self):
        sys.stdout.flush()
        self._saved = os.dup(1)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 1)
        os.close(devnull)

    def __exit__(self, *exc):
        os.dup2(self._saved, 1)
        os.close(self._saved)


def ensure_dir(path):
    os.makedirs(path, exist_ok=True)
    return path


def clean_dir(path):
    shutil.rmtree(path, ignore_errors=True)
    return ensure_dir(path)

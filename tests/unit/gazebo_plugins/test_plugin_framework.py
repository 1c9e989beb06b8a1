"""gazebo_plugins/: PluginParams' warnings and fallbacks, and PluginManager's handling of unknown, refused and
failing plugins (the world server must never die of a plugin)."""
import pytest

from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError, PluginParams
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY, Registry
from racebot_sim_bridge.engine.sim_time import NS, to_ns
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.description.urdf_model import GazeboPlugin, RobotModel

from fakes import FakeLog


class Sim:
    set_step_hook = Simulator.set_step_hook  # the Simulator's own hook bookkeeping

    def __init__(self):
        self.on_spawn, self.on_delete, self.on_reset, self.before_physics, self.after_step = [], [], [], [], []
        self.world = None


class Robot:
    def __init__(self, plugins):
        self.name = 'bot'
        self.model = RobotModel('bot', plugins=plugins)


def params(**values):
    warnings = []
    return PluginParams(GazeboPlugin('p', 'libx.so', {k: v for k, v in values.items()}), warnings.append), warnings


def test_missing_values_take_the_default_silently():
    p, warnings = params()
    assert (p.number('a', 1.5), p.integer('b', 3), p.boolean('c', True), p.string('d', 'x'),
            p.vector('e', 3, (0, 0, 0)), p.choice('f', ('world', 'encoder'), 'world')) == \
        (1.5, 3, True, 'x', (0, 0, 0), 'world')
    assert warnings == []


def test_present_values_are_read():
    p, warnings = params(a='2.5', b='7', c='false', e='1 2 3', f='encoder', g='0')
    assert (p.number('a', 1.0), p.integer('b', 3), p.boolean('c', True), p.vector('e', 3, (0, 0, 0)),
            p.choice('f', ('world', 'encoder'), 'world'), p.boolean('g', True)) == \
        (2.5, 7, False, (1.0, 2.0, 3.0), 'encoder', False)
    assert warnings == []


@pytest.mark.parametrize('tag,text,call,expected', [
    ('wheelSeparation', 'wide', lambda p: p.number('wheelSeparation', 0.34, minimum=0, exclusive=True), 0.34),
    ('wheelSeparation', '-0.3', lambda p: p.number('wheelSeparation', 0.34, minimum=0, exclusive=True), 0.34),
    ('wheelSeparation', '0', lambda p: p.number('wheelSeparation', 0.34, minimum=0, exclusive=True), 0.34),
    ('updateRate', 'nan', lambda p: p.number('updateRate', 100.0, minimum=0), 100.0),
    ('legacyMode', 'maybe', lambda p: p.boolean('legacyMode', True), True),
    ('odometrySource', 'gps', lambda p: p.choice('odometrySource', ('world', 'encoder'), 'world'), 'world'),
    ('xyzOffset', '1 2', lambda p: p.vector('xyzOffset', 3, (0, 0, 0)), (0, 0, 0)),
    ('samples', '2.5', lambda p: p.integer('samples', 5, minimum=1), 5),
])
def test_bad_values_warn_with_the_tag_and_the_value_used(tag, text, call, expected):
    p, warnings = params(**{tag: text})
    assert call(p) == expected
    assert len(warnings) == 1 and tag in warnings[0] and text in warnings[0] and 'using' in warnings[0]


class Recorder(ModelPlugin):
    libraries = ('libgazebo_ros_recorder.so',)

    def __init__(self, ctx, robot, spec):
        if spec.params.get('refuse'):
            raise PluginError('<refuse> says so')
        super().__init__(ctx, robot, spec)
        self.calls = []
        ctx.made.append(self)

    def before_physics(self, time):
        self.calls.append(('before', time))

    def after_step(self, time):
        if self.spec.params.get('fail'):
            raise ZeroDivisionError('boom')
        self.calls.append(('after', time))

    def reset(self):
        self.calls.append(('reset',))

    def close(self):
        self.calls.append(('close',))


def manager(*plugins):
    log, sim = FakeLog(), Sim()
    # the Recorder for the model plugins (so hector_gazebo_ros_gps is not simulated here), the rest as registered
    others = {c for c in REGISTRY.classes.values() if c.plugin_kind is not PluginKind.MODEL}
    m = PluginManager(log, sim, registry=Registry([Recorder, *others]))
    m.made = []
    robot = Robot(list(plugins))
    for hook in sim.on_spawn:
        hook(robot)
    return m, log, sim, robot


def test_unknown_plugins_get_one_warning_each_naming_it_and_the_readme_table():
    m, log, sim, robot = manager(GazeboPlugin('ctrl', 'libgazebo_ros_control.so'),
                                 GazeboPlugin('gps', 'libhector_gazebo_ros_gps.so'),
                                 GazeboPlugin('rec', 'libgazebo_ros_recorder.so'))
    warnings = [t for kind, t in log.lines if kind == 'warn']
    assert len(warnings) == 1
    assert 'libhector_gazebo_ros_gps.so' in warnings[0] and "'gps'" in warnings[0]
    assert 'Supported plugins, sensors and controllers' in warnings[0]
    assert len(m.made) == 1  # gazebo_ros_control is simulator.py's, never warned about here


def test_a_refused_plugin_is_an_error_with_the_reason_and_the_rest_is_built():
    m, log, sim, robot = manager(GazeboPlugin('bad', 'libgazebo_ros_recorder.so', {'refuse': '1'}),
                                 GazeboPlugin('good', 'libgazebo_ros_recorder.so'))
    errors = [t for kind, t in log.lines if kind == 'error']
    assert len(errors) == 1 and '<refuse> says so' in errors[0] and "'bad'" in errors[0]
    assert [p.spec.name for p in m.made] == ['good']


def test_hooks_run_in_order_and_a_failing_plugin_is_stopped_while_the_others_go_on():
    m, log, sim, robot = manager(GazeboPlugin('ok', 'libgazebo_ros_recorder.so'),
                                 GazeboPlugin('broken', 'libgazebo_ros_recorder.so', {'fail': '1'}))
    ok, broken = m.made
    for t in (0.001, 0.002):
        for hook in sim.before_physics:
            hook(t)
        for hook in sim.after_step:
            hook(t)
    for hook in sim.on_reset:
        hook()
    assert ok.calls == [('before', 0.001), ('after', 0.001), ('before', 0.002), ('after', 0.002), ('reset',)]
    assert broken.calls == [('before', 0.001), ('close',)]
    errors = [t for kind, t in log.lines if kind == 'error']
    assert len(errors) == 1 and 'ZeroDivisionError' in errors[0] and 'broken' in errors[0]
    for hook in sim.on_delete:
        hook(robot)
    assert ok.calls[-1] == ('close',) and m.plugins == {}


class BeforeOnly(Recorder):
    libraries = ('libgazebo_ros_before_only.so',)
    after_step = ModelPlugin.after_step  # the base's no-op: nothing to do after the step


def test_only_the_hooks_a_plugin_has_are_called_at_each_update():
    log, sim = FakeLog(), Sim()
    m = PluginManager(log, sim, registry=Registry([BeforeOnly]))
    m.made = []
    for hook in sim.on_spawn:
        hook(Robot([GazeboPlugin('b', 'libgazebo_ros_before_only.so')]))
    assert sim.before_physics == [m.before_physics] and sim.after_step == []  # no call per update for nothing
    sim.before_physics[0](0.001)
    assert m.made[0].calls == [('before', 0.001)]


class Clocked(ModelPlugin):
    """A plugin with its own update clock, as the IMU and the diff drive: it acts (publishes) when <period> ms
    have passed since it last did, and says so as its quiet span (none without a period: called every update).
    <every>: work at every update too (every_update); <fail_at>: its before_physics raises from then on (ms)."""
    libraries = ('libgazebo_ros_clocked.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        self.period = int(spec.params.get('period', '0')) * NS // 1000
        self.fail_at = int(spec.params.get('fail_at', '0')) * NS // 1000
        self.last = None  # when it last acted, in ns
        self.events = ctx.events
        if spec.params.get('every'):
            self.every_update = lambda now: self.events.append((self.spec.name, 'every', now * 1000 // NS))

    def before_physics(self, time):
        now = to_ns(time)
        self.events.append((self.spec.name, 'call', now * 1000 // NS))
        if self.fail_at and now >= self.fail_at:
            raise ZeroDivisionError('boom')
        if self.last is None or now - self.last >= self.period:
            self.last = now
            self.events.append((self.spec.name, 'act', now * 1000 // NS))

    def quiet_span(self):
        return None if not self.period else (self.last, self.last + self.period)

    def reset(self):
        self.last = None  # due at the next update, whatever the time
        self.events.append((self.spec.name, 'reset'))


def clocked(*plugins):
    """A PluginManager with Clocked plugins named by their params; the events of all of them, in order."""
    log, sim = FakeLog(), Sim()
    m = PluginManager(log, sim, registry=Registry([Clocked]))
    m.events = []
    robot = Robot([GazeboPlugin(name, 'libgazebo_ros_clocked.so', params) for name, params in plugins])
    for hook in sim.on_spawn:
        hook(robot)
    return m, log, sim, robot


def update(sim, ms):
    for k in ms:
        for hook in sim.before_physics:
            hook(k / 1000.0)


def of(m, name, kind):
    return [e[2] for e in m.events if e[:2] == (name, kind)]


def test_a_plugin_is_not_called_inside_its_quiet_span_and_is_at_the_first_update_past_it():
    m, log, sim, robot = clocked(('five', {'period': '5'}), ('three', {'period': '3'}), ('always', {}))
    update(sim, range(1, 13))  # a 1 kHz world
    assert of(m, 'five', 'call') == of(m, 'five', 'act') == [1, 6, 11]
    assert of(m, 'three', 'call') == of(m, 'three', 'act') == [1, 4, 7, 10]
    assert of(m, 'always', 'call') == list(range(1, 13))  # no quiet span (None): every update


def test_every_update_runs_at_every_update_before_any_before_physics():
    m, log, sim, robot = clocked(('five', {'period': '5'}), ('encoder', {'period': '5', 'every': '1'}),
                                 ('imu', {'period': '3', 'every': '1'}))
    update(sim, range(1, 13))
    for name in ('encoder', 'imu'):
        assert of(m, name, 'every') == list(range(1, 13))  # quiet or not
    for k in range(1, 13):
        kinds = [kind for name, kind, t in m.events if t == k and kind != 'act']
        assert kinds[:2] == ['every', 'every'] and 'every' not in kinds[2:], (k, kinds)
    assert of(m, 'encoder', 'call') == [1, 6, 11] and of(m, 'imu', 'call') == [1, 4, 7, 10]


def test_time_going_back_calls_every_plugin_again():
    m, log, sim, robot = clocked(('five', {'period': '5'}), ('three', {'period': '3'}))
    update(sim, range(1, 4))
    assert of(m, 'five', 'call') == [1] and of(m, 'three', 'call') == [1]
    for hook in sim.on_reset:  # reset_simulation: the plugins' Reset, then the time starts again from 0
        hook()
    update(sim, range(1, 8))  # 1 ms is inside the quiet spans they had before the reset
    assert of(m, 'five', 'call') == [1, 1, 6] and of(m, 'three', 'call') == [1, 1, 4, 7]


def test_a_plugin_whose_update_raises_is_stopped_and_the_others_keep_their_spans():
    # the failing plugin first: when it leaves, the others' spans must not shift onto each other
    m, log, sim, robot = clocked(('bad', {'period': '3', 'fail_at': '4'}), ('five', {'period': '5'}),
                                 ('always', {}), ('seven', {'period': '7', 'every': '1'}))
    update(sim, range(1, 23))
    assert of(m, 'bad', 'call') == [1, 4] and [p.spec.name for p in m.plugins['bot']] == ['five', 'always', 'seven']
    errors = [t for kind, t in log.lines if kind == 'error']
    assert len(errors) == 1 and 'ZeroDivisionError' in errors[0] and "'bad'" in errors[0]
    assert of(m, 'always', 'call') == list(range(1, 23))
    assert of(m, 'seven', 'every') == list(range(1, 23))
    # each acts on its own clock, and past the update that stopped `bad` is called only when due again
    assert of(m, 'five', 'act') == [1, 6, 11, 16, 21] and [t for t in of(m, 'five', 'call') if t > 5] == [6, 11, 16, 21]
    assert of(m, 'seven', 'act') == [1, 8, 15, 22] and [t for t in of(m, 'seven', 'call') if t > 5] == [8, 15, 22]


def test_encoder_odometry_integrates_every_updates_wheel_speeds_whatever_the_plugins_rates(tmp_path):
    """The diff drive's encoder is its every_update: while PluginManager skips the drive and the IMU between
    their 50 Hz updates, the odometry is still kinematics.differential.encoder_step over every world update."""
    from racebot_sim_bridge.gazebo_plugins.gazebo_ros_diff_drive import DiffDrive
    from racebot_sim_bridge.kinematics import differential as kin

    from model_plugin_sim import fixture_urdf
    from diff_drive_world import command, spawn

    w, robot = spawn(tmp_path, fixture_urdf('diffbot_plugins'))
    try:
        plugins = w.manager.plugins['diffbot']
        drive = next(p for p in plugins if isinstance(p, DiffDrive))
        assert {type(p).__name__ for p in plugins} == {'DiffDrive', 'Imu'}
        assert all(p.quiet_span() is not None for p in plugins)  # both skipped between their updates
        body, indices = robot.body.id, [robot.body.joints[n].index for n in ('left_wheel_joint', 'right_wheel_joint')]
        wheels = []  # (update time in ns, left, right rad/s) as the physics step is about to run

        def read(t):
            left, right = w.sim.world.client.getJointStates(body, indices)
            wheels.append((to_ns(t), left[1], right[1]))
        w.sim.set_step_hook('before_physics', read, True)
        command(w, 0.3, 0.5)
        w.run(0.6)
        command(w, -0.2, -1.2)
        w.run(0.6)
        assert len(wheels) == 1200
        pose, last = (0.0, 0.0, 0.0), 0
        integrated = {}
        for now, left, right in wheels:
            pose, _ = kin.encoder_step(pose, left, right, 0.15, 0.34, (now - last) / float(NS))
            integrated[now], last = pose, now
        assert drive.encoder_pose == pose
        assert abs(pose[0]) + abs(pose[1]) > 0.05 and abs(pose[2]) > 0.1  # it drove and turned
        odom = w.fake.publishers['/odom'].messages
        assert len(odom) > 50  # 50 Hz: the drive was skipped at most updates
        for msg in (odom[len(odom) // 2], odom[-1]):
            x, y, _ = integrated[msg.header.stamp.to_nsec()]
            assert (msg.pose.pose.position.x, msg.pose.pose.position.y) == (x, y)
    finally:
        w.close()

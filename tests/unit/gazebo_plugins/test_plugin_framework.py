"""gazebo_plugins/: PluginParams' warnings and fallbacks, and PluginManager's handling of unknown, refused and
failing plugins (the world server must never die of a plugin)."""
import pytest

from racebot_sim_bridge.gazebo_plugins import PluginKind
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError, PluginParams
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY, Registry
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.description.urdf_model import GazeboPlugin, RobotModel


class Log:
    def __init__(self):
        self.lines = []

    def logwarn(self, m):
        self.lines.append(('warn', m))

    def logerr(self, m):
        self.lines.append(('error', m))

    def loginfo(self, m):
        self.lines.append(('info', m))


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
    log, sim = Log(), Sim()
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
    log, sim = Log(), Sim()
    m = PluginManager(log, sim, registry=Registry([BeforeOnly]))
    m.made = []
    for hook in sim.on_spawn:
        hook(Robot([GazeboPlugin('b', 'libgazebo_ros_before_only.so')]))
    assert sim.before_physics == [m.before_physics] and sim.after_step == []  # no call per update for nothing
    sim.before_physics[0](0.001)
    assert m.made[0].calls == [('before', 0.001)]

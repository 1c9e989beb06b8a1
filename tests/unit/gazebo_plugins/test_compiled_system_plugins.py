"""Compiled system plugins (issue 39): gzserver's -s LIBRARY, built against racebot's Gazebo 11 plugin API
(tests/fixtures/gazebo_plugin_project/system_probe.cc, written as gazebo_ros_api_plugin is), loaded into a real
Simulator in gazebo_shared::setup's order: every Load(argc, argv) with gzserver's command line, every Init, then the
world's worldCreated event, where the plugin finds the world and connects its update; Server::SigInt's stop and
sigInt at a signal. One that is missing, of another kind or throws is reported and the world goes on."""
import pytest

from racebot_sim_bridge.world_server import parse_args, server_plugins

from test_compiled_plugins import driver, joint_state, lines, robot

ARGV = ['/opt/ros/noetic/lib/gazebo_ros/gzserver', '-e', 'ode', '-s', 'libsystem_probe.so', 'worlds/empty.world',
        '__name:=gazebo']


def test_gzservers_command_line_names_its_system_plugins_in_order():
    argv = ['-s', 'liba.so', '--server-plugin', 'libb.so', '--server-plugin=libc.so', '-u', 'w.world', '-s', '']
    assert server_plugins(argv) == ['liba.so', 'libb.so', 'libc.so']
    world, paused, _, ignored = parse_args(argv)
    assert (world, paused, ignored) == ('w.world', True, [])  # taken, not "ignored"


def test_a_system_plugin_loads_before_the_world_then_meets_it_at_world_created(world, capfd):
    compiled = world.manager.compiled
    assert compiled.load_system(['libsystem_probe.so'], ARGV) == 1
    out = capfd.readouterr().out
    # Load got gzserver's whole command line, argv[argc] null as main's; Init came after it, before the world
    assert lines(out, 'SystemProbe') == [
        '[Msg] SystemProbe Load argc 7 terminated args -e ode -s libsystem_probe.so worlds/empty.world __name:=gazebo',
        '[Msg] SystemProbe Init with the world not created yet']
    r = world.spawn('spinner', robot(driver('velocity', 1.5)), '/', (0.0, 0.0, 0.1))
    compiled.world_created()
    world.run(0.2)
    out = capfd.readouterr().out
    assert lines(out, 'SystemProbe') == [
        '[Msg] SystemProbe worldCreated default models spinner first arg -e',  # the argv it kept is still good
        '[Msg] SystemProbe update 100 iterations 100 models 1 sim 0.1',
        '[Msg] SystemProbe update 200 iterations 200 models 1 sim 0.2'], out
    assert joint_state(r).velocity == pytest.approx(1.5, abs=1e-3)  # the model's own plugin beside it
    # reset_world (ResetEntities of the models: the time goes on); Gazebo calls no SystemPlugin::Reset, and the
    # plugin's update goes on counting
    world.sim.reset_world()
    world.run(0.1)
    assert lines(capfd.readouterr().out, 'SystemProbe') == ['[Msg] SystemProbe update 300 iterations 300 models 1 '
                                                           'sim 0.3']
    compiled.sig_int()
    world.manager.close()
    assert lines(capfd.readouterr().out, 'SystemProbe') == [
        '[Msg] SystemProbe stop', '[Msg] SystemProbe sigInt',  # Server::SigInt
        '[Msg] SystemProbe stop',  # Server::Fini's Stop, as the host closes
        '[Msg] SystemProbe destroyed after 300 updates']
    assert world.errors() == []



def test_two_system_plugins_are_each_loaded_before_either_is_initialised(world, capfd):
    """gazebo_shared::setup: every system plugin's Load, then every one's Init; both meet the world."""
    compiled = world.manager.compiled
    assert compiled.load_system(['libsystem_probe.so', 'libsystem_probe.so'], ARGV) == 2
    said = [line.split(' with ')[0].split(' argc ')[0] for line in lines(capfd.readouterr().out, 'SystemProbe')]
    assert said == ['[Msg] SystemProbe Load', '[Msg] SystemProbe Load', '[Msg] SystemProbe Init',
                    '[Msg] SystemProbe Init']
    world.spawn('spinner', robot(), '/', (0.0, 0.0, 0.1))
    compiled.world_created()
    assert lines(capfd.readouterr().out, 'SystemProbe') == [
        '[Msg] SystemProbe worldCreated default models spinner first arg -e'] * 2

def test_gazebo_ros_system_plugins_are_the_world_server_itself(world):
    compiled = world.manager.compiled
    assert compiled.load_system(['libgazebo_ros_paths_plugin.so', '/opt/lib/libgazebo_ros_api_plugin.so'], ARGV) == 0
    said = [m for level, m in world.fake.logs if level == 'info']
    assert len(said) == 2 and all('not loaded' in m for m in said), world.fake.logs
    assert compiled.host is None and world.errors() == []


@pytest.mark.parametrize('filenames, argv, reason', [
    (['libnobody_built.so'], ARGV, 'no library libnobody_built.so was found on GAZEBO_PLUGIN_PATH'),
    (['libworld_counter.so'], ARGV, 'is not a system plugin'),
    (['libsystem_probe.so'], ARGV + ['--probe-throw=load'], 'SystemProbe: thrown in Load'),
    (['libsystem_probe.so'], ARGV + ['--probe-throw=init'], 'in Init: SystemProbe: thrown in Init'),
])
def test_a_system_plugin_that_cannot_run_is_reported_and_the_world_goes_on(world, capfd, filenames, argv, reason):
    compiled = world.manager.compiled
    assert compiled.load_system(filenames, argv) == 0
    errors = world.errors()
    assert len(errors) == 1 and reason in errors[0] and 'The world server runs without it' in errors[0], errors
    assert filenames[0] in errors[0]
    assert compiled.plugins == {}
    r = world.spawn('spinner', robot(driver('velocity', 1.0)), '/', (0.0, 0.0, 0.1))
    compiled.world_created()
    world.run(0.1)
    assert joint_state(r).velocity == pytest.approx(1.0, abs=1e-3)
    if 'Init' in reason:  # loaded, then unloaded: its destructor ran
        assert 'SystemProbe destroyed after 0 updates' in capfd.readouterr().out

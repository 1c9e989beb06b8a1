"""The compatibility interface packages must be wire-identical to upstream.

On the ROS wire a message or service type is its name plus an md5 sum over its fields and
constants. The table below is the md5 table of the project's interface reference (INTERFACES.md)
(what a genpy build of the upstream definitions gives); every generated class must carry exactly that
sum, or clients built against the real packages (rqt, rostopic, ros_control's spawner, scripts calling
/gazebo/*) cannot talk to the simulator.

Needs the workspace built and sourced (``source devel/setup.bash``) but no master. Where an
underlay has the real package, ours steps aside and these imports get the real one, which must
match too.

Also checks that the spawner's command line accepts the documented ros_control options.
"""

import importlib

import pytest

# (type, md5) as in INTERFACES.md; "(srv)" rows are services.
EXPECTED = [
    ('ackermann_msgs/AckermannDrive', '3512e91b48d69674a0e86fadf1ea8231'),
    ('ackermann_msgs/AckermannDriveStamped', '1fd5d7f58889cefd44d29f6653240d0c'),
    ('controller_manager_msgs/ControllerState', 'aeb6b261d97793ab74099a3740245272'),
    ('controller_manager_msgs/HardwareInterfaceResources', 'f25b55cbf1d1f76e82e5ec9e83f76258'),
    ('controller_manager_msgs/ControllerStatistics', '697780c372c8d8597a1436d0e2ad3ba8'),
    ('controller_manager_msgs/ControllersStatistics', 'a154c347736773e3700d1719105df29d'),
    ('controller_manager_msgs/LoadController (srv)', '647e5c54b8d6468952d8d31f1efe96c0'),
    ('controller_manager_msgs/UnloadController (srv)', '647e5c54b8d6468952d8d31f1efe96c0'),
    ('controller_manager_msgs/SwitchController (srv)', 'b29a7abc673b2c54c14b54e50f8d06a5'),
    ('controller_manager_msgs/ListControllers (srv)', '1341feb2e63fa791f855565d0da950d8'),
    ('controller_manager_msgs/ListControllerTypes (srv)', 'c1d4cd11aefa9f97ba4aeb5b33987f4e'),
    ('controller_manager_msgs/ReloadControllerLibraries (srv)', '40e8c411fd1797d2e2c486018f846040'),
    ('control_msgs/JointControllerState', '987ad85e4756f3aef7f1e5e7fe0595d1'),
    ('std_srvs/Empty (srv)', 'd41d8cd98f00b204e9800998ecf8427e'),
    ('rosgraph_msgs/Clock', 'a9c97c1d230cfc112e270351a944ee47'),
]

# Every type of Noetic's gazebo_msgs: the table "Every gazebo_msgs type" of INTERFACES.md (34).
GAZEBO_MSGS = [
    ('gazebo_msgs/ContactState', '48c0ffb054b8c444f870cecea1ee50d9'),
    ('gazebo_msgs/ContactsState', 'acbcb1601a8e525bf72509f18e6f668d'),
    ('gazebo_msgs/LinkState', '0818ebbf28ce3a08d48ab1eaa7309ebe'),
    ('gazebo_msgs/LinkStates', '48c080191eb15c41858319b4d8a609c2'),
    ('gazebo_msgs/ModelState', '9330fd35f2fcd82d457e54bd54e10593'),
    ('gazebo_msgs/ModelStates', '48c080191eb15c41858319b4d8a609c2'),
    ('gazebo_msgs/ODEJointProperties', '1b744c32a920af979f53afe2f9c3511f'),
    ('gazebo_msgs/ODEPhysics', '667d56ddbd547918c32d1934503dc335'),
    ('gazebo_msgs/PerformanceMetrics', '884f71fd5037b886ec5e126b83c4425a'),
    ('gazebo_msgs/SensorPerformanceMetric', '01762ded18cfe9ebc7c8222667c99547'),
    ('gazebo_msgs/WorldState', 'de1a9de3ab7ba97ac0e9ec01a4eb481e'),
    ('gazebo_msgs/ApplyBodyWrench (srv)', '585b9f9618aa0581b207e2f2d90866bc'),
    ('gazebo_msgs/ApplyJointEffort (srv)', 'c0039811b8cc919490b3cff748cdf46b'),
    ('gazebo_msgs/BodyRequest (srv)', '5eade9afe7f232d78005bd0cafeab755'),
    ('gazebo_msgs/DeleteLight (srv)', 'ae11ea8100d536d5b92c2b5917abf912'),
    ('gazebo_msgs/DeleteModel (srv)', '9ce56b4e9e54616de25d796dc972a262'),
    ('gazebo_msgs/GetJointProperties (srv)', '7b30be900f50aa21efec4a0ec92d91c9'),
    ('gazebo_msgs/GetLightProperties (srv)', 'df2cef87e13e2e6990e81e8aaa454c19'),
    ('gazebo_msgs/GetLinkProperties (srv)', '0e06a70386d0ee3fb880c02f23fcd821'),
    ('gazebo_msgs/GetLinkState (srv)', '09d6c98cce97b35f7ab9bd70300657ab'),
    ('gazebo_msgs/GetModelProperties (srv)', '5717f7bd34ed990fa80e28b3015027a3'),
    ('gazebo_msgs/GetModelState (srv)', '4c515e936d3319c9610c559c60bfc3d4'),
    ('gazebo_msgs/GetPhysicsProperties (srv)', '575a5e74786981b7df2e3afc567693a6'),
    ('gazebo_msgs/GetWorldProperties (srv)', '36bb0f2eccf4d8be971410c22818ba3f'),
    ('gazebo_msgs/JointRequest (srv)', '0be1351618e1dc030eb7959d9a4902de'),
    ('gazebo_msgs/SetJointProperties (srv)', '15a76e921b1410c698d82782ea5fa370'),
    ('gazebo_msgs/SetJointTrajectory (srv)', '88f5c10979e3f9649d5ae87a3b12aa65'),
    ('gazebo_msgs/SetLightProperties (srv)', 'e6f13430c57278bb364aca53a1bf5ebf'),
    ('gazebo_msgs/SetLinkProperties (srv)', 'd534ce1b36ee99de0ffa806c3a6348f0'),
    ('gazebo_msgs/SetLinkState (srv)', '8a5146eb66ae4d26b0860b08f3f271be'),
    ('gazebo_msgs/SetModelConfiguration (srv)', '10e3139d3b669c40afc057d38956fff7'),
    ('gazebo_msgs/SetModelState (srv)', '5b3ab0281d4f5445def017e3a2e4a07b'),
    ('gazebo_msgs/SetPhysicsProperties (srv)', '97e2057080558ce4730434b5fae75c91'),
    ('gazebo_msgs/SpawnModel (srv)', '9ed9c82c96abe1a00c3e8cdaeee24413'),
]
ALL_TYPES = EXPECTED + GAZEBO_MSGS


def load_type(spec):
    """'pkg/Name' or 'pkg/Name (srv)' -> the generated class."""
    is_srv = spec.endswith('(srv)')
    package, name = spec.split(' ')[0].split('/')
    module_name = '%s.%s' % (package, 'srv' if is_srv else 'msg')
    try:
        module = importlib.import_module(module_name)
    except ImportError as exc:
        pytest.fail('cannot import %s (%s): build the workspace and `source devel/setup.bash` '
                    'first' % (module_name, exc))
    if not hasattr(module, name):
        pytest.fail('%s has no %s: the package does not define it' % (module_name, name))
    return getattr(module, name)


@pytest.mark.parametrize('spec,md5', ALL_TYPES, ids=[spec for spec, _ in ALL_TYPES])
def test_md5_matches_upstream(spec, md5):
    cls = load_type(spec)
    assert cls._md5sum == md5, (
        '%s: md5 %s, upstream %s; field types, names, order and constants must match upstream'
        % (spec, cls._md5sum, md5))
    assert cls._type == spec.split(' ')[0]


def test_gazebo_msgs_carries_every_noetic_type_and_no_other():
    assert len(GAZEBO_MSGS) == 34 and len({spec for spec, _ in GAZEBO_MSGS}) == 34
    listed = {spec.split(' ')[0].split('/')[1] for spec, _ in GAZEBO_MSGS}
    defined = set()
    for kind in ('msg', 'srv'):
        module = importlib.import_module('gazebo_msgs.' + kind)
        defined |= {name for name, cls in vars(module).items()  # a service's class, not its Request/Response
                    if isinstance(cls, type) and getattr(cls, '_type', '') == 'gazebo_msgs/' + name
                    and (kind == 'msg' or hasattr(cls, '_request_class'))}
    assert defined == listed, 'missing: %s; not in Noetic: %s' % (sorted(listed - defined), sorted(defined - listed))


def test_switch_controller_constants():
    from controller_manager_msgs.srv import SwitchControllerRequest
    assert SwitchControllerRequest.BEST_EFFORT == 1
    assert SwitchControllerRequest.STRICT == 2
    request = SwitchControllerRequest()
    assert request.start_asap is False
    assert request.timeout == 0.0


# -- the spawner's command line (pure parsing, no master) -------------------------------------

def _spawner():
    module = pytest.importorskip('controller_manager.spawner')
    if not getattr(importlib.import_module('controller_manager'), 'RACEBOT_COMPAT', False):
        pytest.skip('controller_manager is the real ros_control package (ours steps aside)')
    return module


def test_spawner_defaults():
    spawner = _spawner()
    options = spawner.parse_args(['joint_state_controller', 'left_rear_wheel_velocity_controller'])
    assert options.controllers == ['joint_state_controller', 'left_rear_wheel_velocity_controller']
    assert options.stopped is False
    assert options.wait_for is None
    assert options.namespace is None
    assert options.timeout == 30.0
    assert options.no_timeout is False
    assert options.shutdown_timeout is None
    assert spawner.startup_timeout(options) == 30.0


def test_spawner_all_documented_options():
    spawner = _spawner()
    options = spawner.parse_args([
        '--stopped', '--wait-for', '/calibrated', '--namespace', '/racebot', '--timeout', '12.5',
        '--shutdown-timeout', '3', 'a', 'b', 'c'])
    assert options.stopped is True
    assert options.wait_for == '/calibrated'
    assert options.namespace == '/racebot'
    assert options.timeout == 12.5
    assert options.shutdown_timeout == 3.0  # accepted; the node warns that it is ignored
    assert options.controllers == ['a', 'b', 'c']


def test_spawner_no_timeout():
    spawner = _spawner()
    assert spawner.startup_timeout(spawner.parse_args(['--no-timeout', 'a'])) is None
    assert spawner.startup_timeout(spawner.parse_args(['--timeout', '0', 'a'])) is None


@pytest.mark.parametrize('argv', [[], ['--timeout', 'soon', 'a'], ['--timeout', '-1', 'a'],
                                  ['--bogus', 'a']])
def test_spawner_rejects_bad_command_lines(argv):
    spawner = _spawner()
    with pytest.raises(SystemExit) as info:
        spawner.parse_args(argv)
    assert info.value.code == 2


def test_spawner_service_names():
    spawner = _spawner()
    assert spawner.service_names() == ('controller_manager/load_controller',
                                       'controller_manager/switch_controller',
                                       'controller_manager/unload_controller')
    assert spawner.service_names('/racebot')[0] == '/racebot/controller_manager/load_controller'
    assert spawner.service_names('racebot/')[2] == 'racebot/controller_manager/unload_controller'


def test_controller_manager_command_parsing():
    pytest.importorskip('controller_manager.cli')
    from controller_manager.cli import parse_command
    assert parse_command(['list']) == ('list', [], False)
    assert parse_command(['lt']) == ('list-types', [], False)
    assert parse_command(['spawn', 'a', 'b']) == ('spawn', ['a', 'b'], False)
    assert parse_command(['kl', 'a']) == ('kill', ['a'], False)
    assert parse_command(['reload-libraries', '--restore']) == ('reload-libraries', [], True)
    assert parse_command(['load']) is None
    assert parse_command(['frobnicate']) is None
    assert parse_command([]) is None

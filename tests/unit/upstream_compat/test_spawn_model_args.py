"""gazebo_ros.spawn_model's pure parts against gazebo_ros's scripts/spawn_model (noetic-devel):
the command line (-urdf|-sdf, one of -file/-param/-database/-stdin, -model required, -reference_frame,
-gazebo_namespace, -robot_namespace defaulting to the caller's namespace, -unpause, -wait,
-x -y -z -R -P -Y, -J JOINT POSITION repeatable, -package_to_model, -b), the -database snippet,
-package_to_model's rewrite and the Euler angles. No ROS master.
"""
import math
import xml.etree.ElementTree as ET

import pytest

from gazebo_ros.spawn_model import (MODEL_DATABASE_TEMPLATE, build_parser, package_to_model, parse_args,
                                    prepare_xml, quaternion_from_euler)

BASE = ['-urdf', '-param', 'robot_description', '-model', 'racebot']


def test_the_tutorials_command_line():
    args = parse_args(['-urdf', '-model', 'racebot', '-param', 'robot_description'])
    assert args.urdf and not args.sdf
    assert args.param == 'robot_description'
    assert (args.file, args.database, args.stdin) == (None, None, False)
    assert args.model == 'racebot'


def test_defaults_are_upstreams():
    args = parse_args(BASE)
    assert (args.x, args.y, args.z, args.R, args.P, args.Y) == (0, 0, 0, 0, 0, 0)
    assert args.gazebo_namespace == '/gazebo'
    assert args.reference_frame == ''
    assert args.joints == []
    assert (args.unpause, args.wait, args.bond, args.package_to_model) == (False, None, False, False)
    assert args.timeout is None  # waits for the service for ever, as upstream


@pytest.mark.parametrize('caller_namespace', ['/', '/racebot/', '/a/b/'])
def test_robot_namespace_defaults_to_the_callers_namespace(caller_namespace):
    # upstream: default=rospy.get_namespace(), i.e. '/' at the root, '/racebot/' in <group ns="racebot">
    assert parse_args(BASE, caller_namespace).robot_namespace == caller_namespace
    assert parse_args(BASE + ['-robot_namespace', '/mine'], caller_namespace).robot_namespace == '/mine'


def test_every_option():
    args = parse_args(['-sdf', '-file', '/tmp/m.sdf', '-model', 'box', '-robot_namespace', '/rb',
                       '-reference_frame', 'world', '-gazebo_namespace', '/sim', '-x', '1', '-y', '-2.5',
                       '-z', '0.1', '-R', '0.1', '-P', '-0.2', '-Y', '3.14', '-J', 'a_joint', '0.5',
                       '-J', 'b_joint', '-1', '-unpause', '-wait', 'other', '-package_to_model', '-b',
                       '-timeout', '5'])
    assert args.sdf and not args.urdf
    assert args.file == '/tmp/m.sdf'
    assert args.model == 'box'
    assert args.robot_namespace == '/rb'
    assert args.reference_frame == 'world'
    assert args.gazebo_namespace == '/sim'
    assert (args.x, args.y, args.z, args.R, args.P, args.Y) == (1.0, -2.5, 0.1, 0.1, -0.2, 3.14)
    assert args.joints == [('a_joint', 0.5), ('b_joint', -1.0)]
    assert (args.unpause, args.wait, args.package_to_model, args.bond) == (True, 'other', True, True)
    assert args.timeout == 5.0


def test_options_in_any_order():
    args = parse_args(['-model', 'racebot', '-x', '2', '-param', 'robot_description', '-urdf'])
    assert (args.urdf, args.param, args.model, args.x) == (True, 'robot_description', 'racebot', 2.0)


def test_stdin_and_database_sources():
    assert parse_args(['-urdf', '-stdin', '-model', 'm']).stdin is True
    assert parse_args(['-sdf', '-database', 'coke_can', '-model', 'can']).database == 'coke_can'


def test_j_is_repeatable_and_keeps_order():
    args = parse_args(BASE + ['-J', 'b', '2', '-J', 'a', '1', '-J', 'b', '3'])
    assert args.joints == [('b', 2.0), ('a', 1.0), ('b', 3.0)]


# -- errors: argparse's, exit code 2, as upstream's -------------------------------------------------

def _error(argv, capsys):
    with pytest.raises(SystemExit) as info:
        parse_args(argv)
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith('usage: spawn_model')
    return err


def test_model_is_required(capsys):
    assert 'the following arguments are required: -model' in _error(['-urdf', '-param', 'robot_description'],
                                                                     capsys)


def test_model_needs_a_value(capsys):
    assert 'argument -model: expected one argument' in _error(BASE[:-1], capsys)


def test_a_source_is_required(capsys):
    assert 'one of the arguments -file -param -database -stdin is required' in _error(
        ['-urdf', '-model', 'racebot'], capsys)


def test_a_kind_is_required(capsys):
    assert 'one of the arguments -urdf -sdf is required' in _error(
        ['-param', 'robot_description', '-model', 'racebot'], capsys)


@pytest.mark.parametrize('argv, says', [
    (['-urdf', '-sdf', '-param', 'robot_description', '-model', 'm'], 'argument -sdf: not allowed with argument -urdf'),
    (['-urdf', '-param', 'robot_description', '-file', '/tmp/m.urdf', '-model', 'm'],
     'argument -file: not allowed with argument -param'),
    (['-urdf', '-param', 'robot_description', '-stdin', '-model', 'm'],
     'argument -stdin: not allowed with argument -param'),
])
def test_mutually_exclusive_options(argv, says, capsys):
    assert says in _error(argv, capsys)


@pytest.mark.parametrize('argv, says', [
    (BASE + ['-x', 'abc'], "argument -x: expected a number, got 'abc'"),
    (BASE + ['-Y', ''], 'argument -Y: expected a number'),
    (BASE + ['-z', 'nan'], "argument -z: must be a finite number, got 'nan'"),
    (BASE + ['-R', 'inf'], "argument -R: must be a finite number, got 'inf'"),
    (BASE + ['-J', 'a_joint', 'up'], "argument -J: joint a_joint: expected a number, got 'up'"),
    (BASE + ['-timeout', 'soon'], "argument -timeout: expected a number, got 'soon'"),
    (BASE + ['-timeout', '0'], 'argument -timeout: must be more than 0 seconds'),
])
def test_bad_numbers_name_the_option(argv, says, capsys):
    assert says in _error(argv, capsys)


@pytest.mark.parametrize('argv, says', [
    (BASE + ['-x'], 'argument -x: expected one argument'),
    (BASE + ['-J', 'a_joint'], 'argument -J: expected 2 arguments'),
    (BASE + ['-J'], 'argument -J: expected 2 arguments'),
    (['-urdf', '-file'], 'argument -file: expected one argument'),
])
def test_missing_values(argv, says, capsys):
    assert says in _error(argv, capsys)


@pytest.mark.parametrize('option', ['--model', '-foo', '-X', 'stray_word', '-speed'])
def test_unknown_option(option, capsys):
    assert 'unrecognized arguments: %s' % option in _error(BASE + [option], capsys)


def test_help_exits_0_with_every_option(capsys):
    with pytest.raises(SystemExit) as info:
        parse_args(['-h'])
    assert info.value.code == 0
    out = capsys.readouterr().out
    for option in ('-urdf', '-sdf', '-file', '-param', '-database', '-stdin', '-model', '-reference_frame',
                   '-gazebo_namespace', '-robot_namespace', '-unpause', '-wait', '-x', '-Y', '-J JOINT_NAME '
                   'JOINT_POSITION', '-package_to_model', '-b'):
        assert option in out


def test_parser_has_upstreams_destinations():
    # scripts and launch wrappers that build on upstream's parser read these attribute names
    dests = {a.dest for a in build_parser()._actions}
    assert {'urdf', 'sdf', 'file', 'param', 'database', 'stdin', 'model', 'reference_frame', 'gazebo_namespace',
            'robot_namespace', 'unpause', 'wait', 'x', 'y', 'z', 'R', 'P', 'Y', 'joints', 'package_to_model',
            'bond'} <= dests


# -- what is sent -----------------------------------------------------------------------------------

def test_database_snippet_includes_the_model_from_the_model_path():
    root = ET.fromstring(MODEL_DATABASE_TEMPLATE.format('coke_can'))
    assert root.tag == 'sdf'
    assert root.find('world/include/uri').text == 'model://coke_can'


def test_package_to_model_rewrites_package_meshes_only():
    root = ET.fromstring(
        '<robot name="r"><link name="a"><visual><geometry>'
        '<mesh filename="package://racebot_description/meshes/body.stl" scale="1 1 1"/></geometry></visual>'
        '<collision><geometry><mesh filename="file:///abs/body.stl"/></geometry></collision></link>'
        '<link name="b"><visual><geometry><mesh filename="meshes/rel.dae"/></geometry></visual>'
        '<visual><geometry><mesh/></geometry></visual></link>'
        '<gazebo><plugin filename="package://x/y.so"/></gazebo></robot>')
    package_to_model(root)
    meshes = [m.get('filename') for m in root.iter('mesh')]
    assert meshes == ['model://racebot_description/meshes/body.stl', 'file:///abs/body.stl', 'meshes/rel.dae', None]
    assert root.find('gazebo/plugin').get('filename') == 'package://x/y.so'  # only <mesh filename>


def test_prepare_xml_rewrites_only_when_asked():
    text = '<robot name="r"><link name="a"><visual><geometry><mesh filename="package://p/m.stl"/></geometry>' \
           '</visual></link></robot>'
    assert 'package://p/m.stl' in prepare_xml(text)
    assert 'model://p/m.stl' in prepare_xml(text, to_model=True)


def test_prepare_xml_refuses_what_is_not_xml():
    with pytest.raises(ET.ParseError):
        prepare_xml('<robot name="x"><link name="a"></robot')


@pytest.mark.parametrize('rpy', [(0, 0, 0), (0.3, 0, 0), (0, -0.4, 0), (0, 0, 2.5), (0.1, 0.2, 0.3), (-1, 1.2, -3)])
def test_quaternion_from_euler_is_tfs_sxyz(rpy):
    # Rz(yaw) Ry(pitch) Rx(roll) as a rotation matrix, against the quaternion's matrix
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    expected = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                [-sp, cp * sr, cp * cr]]
    x, qy, z, w = quaternion_from_euler(*rpy)
    assert math.isclose(x * x + qy * qy + z * z + w * w, 1.0, rel_tol=1e-12)
    got = [[1 - 2 * (qy * qy + z * z), 2 * (x * qy - z * w), 2 * (x * z + qy * w)],
           [2 * (x * qy + z * w), 1 - 2 * (x * x + z * z), 2 * (qy * z - x * w)],
           [2 * (x * z - qy * w), 2 * (qy * z + x * w), 1 - 2 * (x * x + qy * qy)]]
    for row_e, row_g in zip(expected, got):
        for e, g in zip(row_e, row_g):
            assert math.isclose(e, g, abs_tol=1e-12)

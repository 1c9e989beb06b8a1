"""`$(find xacro)/xacro` expands robot descriptions written for Noetic's xacro (1.14.17).

Each test writes a small document, runs the executable that `$(find xacro)` resolves to (as a
launch file's `command="$(find xacro)/xacro ..."` does, with the venv's python3 first on PATH) and
checks its output, its messages and its exit code. One test per addition of 1.14 over the pinned
1.13.3 (upstream_compat/xacro/src/xacro_noetic names the release of each). No ROS master.
"""
import math
import os
import subprocess
import sys
import textwrap
import xml.dom.minidom
from pathlib import Path

import pytest

from racebot_model import REPO, XACRO_FILE, render_racebot

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _environment():
    env = dict(os.environ)
    paths = [str(REPO)] + ([env['ROS_PACKAGE_PATH']] if env.get('ROS_PACKAGE_PATH') else [])
    env['ROS_PACKAGE_PATH'] = os.pathsep.join(paths)
    env['PATH'] = os.pathsep.join([os.path.dirname(sys.executable), env.get('PATH', '')])
    return env


ENV = _environment()


def _find_xacro():
    """What `$(find xacro)/xacro` in a launch file names, resolved the way roslaunch does."""
    from roslaunch.substitution_args import resolve_args
    old = os.environ.get('ROS_PACKAGE_PATH')
    os.environ['ROS_PACKAGE_PATH'] = ENV['ROS_PACKAGE_PATH']
    try:
        return resolve_args('$(find xacro)/xacro')
    finally:
        if old is None:
            del os.environ['ROS_PACKAGE_PATH']
        else:
            os.environ['ROS_PACKAGE_PATH'] = old


XACRO = _find_xacro()


class Run:
    def __init__(self, process):
        self.code = process.returncode
        self.out = process.stdout
        self.err = process.stderr

    @property
    def root(self):
        assert self.code == 0, self.err
        return xml.dom.minidom.parseString(self.out).documentElement

    def find(self, tag):
        found = self.root.getElementsByTagName(tag)
        assert found, 'no <%s> in\n%s' % (tag, self.out)
        return found[0]


def xacro(tmp_path, body, *args, files=None, root_attrs=''):
    """Expand `<robot xmlns:xacro=...>body</robot>` written to tmp_path/robot.xacro."""
    for name, text in (files or {}).items():
        (tmp_path / name).write_text(textwrap.dedent(text))
    doc = tmp_path / 'robot.xacro'
    doc.write_text('<robot name="r" %s %s>%s</robot>' % (XACRO_NS, root_attrs, textwrap.dedent(body)))
    process = subprocess.run([XACRO] + list(args) + [str(doc)], env=ENV, capture_output=True,
                             text=True, timeout=60)
    return Run(process)


def test_find_xacro_is_our_stand_in():
    assert Path(XACRO).resolve() == (REPO / 'upstream_compat' / 'xacro' / 'xacro').resolve()


# ---- the xacro. namespace ---------------------------------------------------------------------

CONFIG_YAML = """\
wheel:
  radius: 0.05
  names: [front_left, front_right]
sensors:
  - {name: lidar, rate: 40}
  - {name: camera, rate: 30}
"""


def test_xacro_load_yaml_with_dotted_access(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="cfg" value="${xacro.load_yaml('config.yaml')}"/>
        <wheel r="${cfg.wheel.radius}" first="${cfg['wheel'].names[0]}"/>
        <rates v="${[s.rate for s in cfg.sensors]}" second="${cfg.sensors[1].name}"/>''',
                files={'config.yaml': CONFIG_YAML})
    assert run.find('wheel').getAttribute('r') == '0.05'
    assert run.find('wheel').getAttribute('first') == 'front_left'
    assert run.find('rates').getAttribute('v') == '[40, 30]'
    assert run.find('rates').getAttribute('second') == 'camera'


def test_bare_load_yaml_still_works_and_warns(tmp_path):
    run = xacro(tmp_path, '<v r="${load_yaml(\'config.yaml\').wheel.radius}"/>',
                files={'config.yaml': CONFIG_YAML})
    assert run.find('v').getAttribute('r') == '0.05'
    assert 'Using load_yaml() directly is deprecated. Use xacro.load_yaml() instead.' in run.err


def test_yaml_dict_membership_and_a_missing_key(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="cfg" value="${xacro.load_yaml('config.yaml')}"/>
        <v has="${'radius' in cfg.wheel}"/>
        <v missing="${cfg.wheel.mass}"/>''', files={'config.yaml': CONFIG_YAML})
    assert run.code == 2
    assert "The yaml dictionary has no key 'mass'" in run.err


def test_xacro_dotify(tmp_path):
    run = xacro(tmp_path, '<v x="${xacro.dotify(dict(a=dict(b=7))).a.b}"/>')
    assert run.find('v').getAttribute('x') == '7'


def test_yaml_angle_tags(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="u" value="${xacro.load_yaml('units.yaml')}"/>
        <v a="${u.angles}"/>''', files={'units.yaml': 'angles: [!radians pi, !degrees 2*90, !degrees 45]'})
    assert eval(run.find('v').getAttribute('a')) == pytest.approx([math.pi, math.pi, math.pi / 4])


def test_yaml_length_tags_of_noetic_devel(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="u" value="${xacro.load_yaml('units.yaml')}"/>
        <v l="${u.lengths}"/>''',
                files={'units.yaml': 'lengths: [!meters 2.5, !millimeters 25, !foot 1, !inches 2]'})
    assert eval(run.find('v').getAttribute('l')) == pytest.approx([2.5, 0.025, 0.3048, 0.0508])


def test_missing_yaml_file_is_a_clear_error(tmp_path):
    run = xacro(tmp_path, '<v x="${xacro.load_yaml(\'nowhere.yaml\')}"/>')
    assert run.code == 2
    assert run.out == ''
    assert 'No such file or directory' in run.err and str(tmp_path / 'nowhere.yaml') in run.err
    assert 'when processing file: %s' % (tmp_path / 'robot.xacro') in run.err


def test_xacro_abs_filename(tmp_path):
    run = xacro(tmp_path, '<v f="${xacro.abs_filename(\'meshes/a.stl\')}"/>')
    assert run.find('v').getAttribute('f') == str(tmp_path / 'meshes' / 'a.stl')


def test_xacro_arg_reads_command_line_and_defaults_as_text(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:arg name="prefix" default="left"/>
        <xacro:arg name="count" default="${1 + 2}"/>
        <v p="${xacro.arg('prefix')}" c="${xacro.arg('count') + 'x'}"/>''', 'prefix:=right')
    assert run.find('v').getAttribute('p') == 'right'
    assert run.find('v').getAttribute('c') == '3x'  # a default is stored as text (1.14.15)


def test_xacro_tokenize(tmp_path):
    run = xacro(tmp_path, '<v t="${xacro.tokenize(\'a, b;c d\')}"/>')
    assert run.find('v').getAttribute('t') == "['a', 'b', 'c', 'd']"


def test_xacro_messages_print_and_evaluate_to_nothing(tmp_path):
    run = xacro(tmp_path, '''
        <v m="${xacro.message('hello', 2, 3.5, color=32)}"/>
        <w m="${xacro.warning('careful')}"/>
        <e m="${xacro.error('wrong', print_location=False)}"/>
        <p m="${xacro.print_location()}"/>''')
    for tag in 'vwep':
        assert run.find(tag).getAttribute('m') == ''
    lines = run.err.splitlines()
    assert 'hello 2 3.5' in lines
    assert 'warning: careful' in lines
    assert 'error: wrong' in lines
    # warning() and print_location() say where; error(print_location=False) does not
    assert run.err.count('when processing file: %s' % (tmp_path / 'robot.xacro')) == 2


def test_xacro_fatal_stops_with_exit_code_2(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:macro name="wheel" params="radius">
          <xacro:if value="${radius &lt;= 0}">
            ${xacro.fatal('wheel radius must be positive, got', radius)}
          </xacro:if>
        </xacro:macro>
        <xacro:wheel radius="-1"/>''')
    assert run.code == 2
    assert run.out == ''
    assert 'error: wheel radius must be positive, got -1' in run.err
    assert 'when instantiating macro: wheel' in run.err


# ---- python. and math. namespaces, the guarded eval ---------------------------------------------

def test_python_and_math_namespaces(tmp_path):
    run = xacro(tmp_path, '''
        <v r="${list(python.range(3))}" s="${sorted(python.set([3, 1, 3]))}" a="${python.abs(-2)}"
           z="${list(python.zip([1, 2], 'ab'))}" n="${len('abc')}" sm="${python.sum([1, 2])}"
           pi="${math.pi}" rad="${math.radians(180)}" deg="${degrees(math.pi)}"/>''')
    v = run.find('v')
    assert v.getAttribute('r') == '[0, 1, 2]'
    assert v.getAttribute('s') == '[1, 3]'
    assert v.getAttribute('a') == '2'
    assert v.getAttribute('z') == "[(1, 'a'), (2, 'b')]"
    assert v.getAttribute('n') == '3'
    assert v.getAttribute('sm') == '3'
    assert float(v.getAttribute('pi')) == pytest.approx(math.pi)
    assert float(v.getAttribute('rad')) == pytest.approx(math.pi)
    assert float(v.getAttribute('deg')) == pytest.approx(180.0)
    assert 'Using sorted() directly is deprecated. Use python.sorted() instead.' in run.err


def test_comprehensions_see_properties(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="scale" value="2"/>
        <v x="${[v * scale for v in [1, 2]]}"/>''')
    assert run.find('v').getAttribute('x') == '[2, 4]'


def test_double_underscore_names_are_refused(tmp_path):
    run = xacro(tmp_path, '<v x="${().__class__.__bases__}"/>')
    assert run.code == 2
    assert 'Use of invalid name(s):' in run.err and '__class__, __bases__' in run.err


# ---- properties ---------------------------------------------------------------------------------

def test_property_remove(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="p" value="1"/>
        <v x="${p}"/>
        <xacro:property name="p" remove="true"/>
        <w x="${p}"/>''')
    assert run.code == 2
    assert "name 'p' is not defined" in run.err


def test_property_lazy_eval_false_redefines_from_previous_value(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="p" value="ABC"/>
        <xacro:property name="p" value="${p.lower()}" lazy_eval="false"/>
        <v x="${p}"/>''')
    assert run.find('v').getAttribute('x') == 'abc'


def test_circular_definition_suggests_lazy_eval(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="p" value="ABC"/>
        <xacro:property name="p" value="${p.lower()}"/>
        <v x="${p}"/>''')
    assert run.code == 2
    assert 'circular variable definition: p -> p' in run.err
    assert 'Consider disabling lazy evaluation via lazy_eval="false"' in run.err


def test_property_name_from_expression_set_in_callers_scope(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:macro name="square" params="name args">
          <xacro:property name="${name}" value="${[float(x)**2 for x in args]}" scope="parent"/>
        </xacro:macro>
        <xacro:square name="result" args="${python.range(3)}"/>
        <v x="${result}"/>''')
    assert run.find('v').getAttribute('x') == '[0.0, 1.0, 4.0]'


def test_property_names_with_double_underscore_are_refused(tmp_path):
    run = xacro(tmp_path, '<xacro:property name="__hidden" value="1"/>')
    assert run.code == 2
    assert 'Property names must not start with double underscore:__hidden' in run.err


def test_literal_with_underscore_stays_text(tmp_path):
    run = xacro(tmp_path, '<xacro:property name="p" value="1_000"/><v x="${p}" t="${p + \'!\'}"/>')
    assert run.find('v').getAttribute('x') == '1_000'
    assert run.find('v').getAttribute('t') == '1_000!'


# ---- includes -----------------------------------------------------------------------------------

def test_optional_include_of_a_missing_file(tmp_path):
    run = xacro(tmp_path, '<xacro:include filename="absent.xacro" optional="true"/><v/>')
    assert run.find('v') is not None
    run = xacro(tmp_path, '<xacro:include filename="absent.xacro"/><v/>')
    assert run.code == 2
    assert 'No such file or directory' in run.err and 'absent.xacro' in run.err


def test_include_with_child_elements_is_reported(tmp_path):
    run = xacro(tmp_path, '<xacro:include filename="part.xacro"><uri>x</uri></xacro:include>',
                files={'part.xacro': '<part><p/></part>'})
    assert run.find('p') is not None
    assert 'warning: Child elements of a <xacro:include> tag are ignored' in run.err.splitlines()
    assert 'when processing file: %s' % (tmp_path / 'robot.xacro') in run.err


def test_namespaced_include_sees_includer_and_its_own_macros(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="size" value="3"/>
        <xacro:include filename="parts.xacro" ns="parts"/>
        <xacro:parts.outer/>
        <v d="${parts.double}"/>''', files={'parts.xacro': '''\
        <part xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:property name="double" value="${2 * size}"/>
          <xacro:macro name="inner"><inner/></xacro:macro>
          <xacro:macro name="outer"><outer/><xacro:inner/></xacro:macro>
        </part>'''})
    assert run.find('v').getAttribute('d') == '6'
    assert run.find('inner') is not None


def test_plain_tags_are_not_xacro_tags(tmp_path):
    run = xacro(tmp_path, '<property name="p" value="1"/><include filename="absent.xacro"/>')
    assert run.find('property').getAttribute('value') == '1'
    assert run.find('include').getAttribute('filename') == 'absent.xacro'


# ---- macros -------------------------------------------------------------------------------------

def test_macro_defaults_with_spaces_expressions_and_args(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:arg name="side" default="left"/>
        <xacro:property name="w" value="2"/>
        <xacro:macro name="m" params="xyz:='1 2 3' size:=${w * (1 + 1)} side:=$(arg side) last">
          <v xyz="${xyz}" size="${size}" side="${side}" last="${last}"/>
        </xacro:macro>
        <xacro:m last="x"/>''')
    v = run.find('v')
    values = [v.getAttribute(name) for name in ('xyz', 'size', 'side', 'last')]
    assert values == ['1 2 3', '4', 'left', 'x']


def test_macro_defined_in_a_macro_is_local(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:macro name="outer"><xacro:macro name="helper"><h/></xacro:macro><xacro:helper/></xacro:macro>
        <xacro:outer/>''')
    assert run.find('h') is not None
    run = xacro(tmp_path, '''
        <xacro:macro name="outer"><xacro:macro name="helper"><h/></xacro:macro></xacro:macro>
        <xacro:outer/><xacro:helper/>''')
    assert run.code == 2
    assert 'unknown macro name: xacro:helper' in run.err


def test_xml_namespaces_of_a_macro_body_move_up(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:macro name="m" xmlns:foo="http://example.org/foo"><foo:a/></xacro:macro>
        <xacro:m/>''')
    assert run.root.getAttribute('xmlns:foo') == 'http://example.org/foo'


# ---- document -----------------------------------------------------------------------------------

def test_xacro_namespace_and_attributes_leave_the_output(tmp_path):
    run = xacro(tmp_path, '<v xacro:note="x" y="1"/>',
                root_attrs='xacro:targetNamespace="http://example.org/robot"')
    assert 'xmlns:xacro' not in run.out and 'xacro:' not in run.out
    assert run.root.getAttribute('xmlns') == 'http://example.org/robot'
    assert run.find('v').getAttribute('y') == '1'


def test_unknown_attribute_is_reported_with_its_location(tmp_path):
    run = xacro(tmp_path, '<xacro:property name="p" value="1" valeu="2"/><v x="${p}"/>')
    assert run.find('v').getAttribute('x') == '1'
    assert 'warning: xacro:property: unknown attribute(s): valeu' in run.err.splitlines()
    assert 'when processing file: %s' % (tmp_path / 'robot.xacro') in run.err


def test_comment_evaluation_when_switched_on(tmp_path):
    run = xacro(tmp_path, '''
        <xacro:property name="p" value="7"/>
        <!-- plain ${p} -->
        <!-- xacro:eval-comments -->
        <!-- evaluated ${p} -->
        <v/>
        <!-- plain again ${p} -->''')
    comments = [n.data.strip() for n in run.root.childNodes if n.nodeType == n.COMMENT_NODE]
    assert comments == ['plain ${p}', 'evaluated 7', 'plain again ${p}']


def test_unclosed_expression_is_an_error(tmp_path):
    run = xacro(tmp_path, '<v x="${1 + 2"/>')
    assert run.code == 2
    assert 'invalid expression: ${1 + 2' in run.err


# ---- command line -------------------------------------------------------------------------------

def test_command_line_of_1_14(tmp_path):
    run = xacro(tmp_path, '<v/>', '--inorder')
    assert run.code == 0
    assert ('xacro: in-order processing became default in ROS Melodic. You can drop the option.'
            in run.err.splitlines())
    run = xacro(tmp_path, '<v/>', '--legacy')
    assert run.code == 2
    assert 'no such option: --legacy' in run.err


# ---- racebot's own description ------------------------------------------------------------------

def test_racebot_description_expands_as_before(tmp_path):
    """The racebot's xacro through `$(find xacro)/xacro` gives what the pinned 1.13.3 gave, but for
    the root's xmlns:xacro, which 1.14 (from 1.13.4 on) leaves out."""
    before = render_racebot().replace(' ' + XACRO_NS, '', 1)
    process = subprocess.run([XACRO, '--inorder', str(XACRO_FILE)], env=ENV, capture_output=True,
                             text=True, timeout=60)
    assert process.returncode == 0, process.stderr
    banner_end = process.stdout.index('<robot')
    assert process.stdout[banner_end:].strip() == before[before.index('<robot'):].strip()


def test_bare_xacro_on_path_is_the_noetic_one(tmp_path):
    """Noetic-era launch files also write `command="xacro ..."`: the `xacro` that PATH finds in a sourced
    shell (the venv's bin/ comes first) must expand `xacro.` calls too, not only `$(find xacro)/xacro`."""
    import shutil
    bare = shutil.which('xacro', path=ENV['PATH'])
    assert bare, 'no xacro on PATH: run make setup'
    doc = tmp_path / 'robot.xacro'
    doc.write_text('<robot name="r" %s><xacro:property name="n" value="${xacro.dotify(dict(a=3)).a}"/>'
                   '<link name="l${n}"/></robot>' % XACRO_NS)
    process = subprocess.run([bare, str(doc)], env=ENV, capture_output=True, text=True, timeout=60)
    assert process.returncode == 0, '%s: %s' % (bare, process.stderr)
    assert '<link name="l3"/>' in process.stdout

"""racebot's C++ control_toolbox::Pid (upstream_compat/control_toolbox/include/control_toolbox/pid.h) against its
Python port (racebot_sim_bridge/ros_control/pid.py, checked against control_toolbox 1.19's src/pid.cpp).

A small program built with g++ against the header (and the devel space's generated ParametersConfig.h) runs a
script of Pid calls read from stdin and prints each result; the same gains and inputs go through pid.py. Where
pid.py differs from upstream on purpose (its docstring: no derivative kick on the first update, dt <= 0 ignored),
the C++ header must keep upstream's behaviour, which the last tests pin. Needs `make build` and g++; no master.
"""
import math
import random
import shutil
import subprocess
from pathlib import Path

import pytest

from racebot_sim_bridge.ros_control.pid import Pid

ROOT = Path(__file__).resolve().parents[3]
CONFIG_HEADER = ROOT / 'devel' / 'include' / 'control_toolbox' / 'ParametersConfig.h'

# One command a line: gains p i d i_max i_min antiwindup | reset | reset2 d_error i_error | c2 error dt |
# c3 error error_dot dt | errors | cmd. Each prints one line of %.17g values.
RUNNER = r'''
#include <control_toolbox/pid.h>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

// strtod, unlike operator>>, reads nan and inf
static double number()
{
  std::string token;
  std::cin >> token;
  return std::strtod(token.c_str(), nullptr);
}

int main()
{
  control_toolbox::Pid pid;
  std::string op;
  while (std::cin >> op)
  {
    if (op == "gains")
    {
      const double p = number(), i = number(), d = number(), i_max = number(), i_min = number();
      pid.setGains(p, i, d, i_max, i_min, number() != 0.0);
      std::printf("ok\n");
    }
    else if (op == "reset")
    {
      pid.reset();
      std::printf("ok\n");
    }
    else if (op == "reset2")
    {
      const double d_error = number();
      pid.reset(d_error, number());
      std::printf("ok\n");
    }
    else if (op == "c2")
    {
      const double error = number();
      const double dt = number();
      std::printf("%.17g\n", pid.computeCommand(error, ros::Duration(dt)));
    }
    else if (op == "c3")
    {
      const double error = number();
      const double error_dot = number();
      const double dt = number();
      std::printf("%.17g\n", pid.computeCommand(error, error_dot, ros::Duration(dt)));
    }
    else if (op == "errors")
    {
      double pe, ie, de;
      pid.getCurrentPIDErrors(&pe, &ie, &de);
      std::printf("%.17g %.17g %.17g\n", pe, ie, de);
    }
    else if (op == "cmd")
    {
      std::printf("%.17g\n", pid.getCurrentCmd());
    }
    std::fflush(stdout);
  }
  return 0;
}
'''

# (p, i, d, i_clamp_min, i_clamp_max, antiwindup): integral term clamped, integral state clamped (with a negative i
# too), and i_clamp 0 (no integral term at all without antiwindup).
GAINS = [
    (2.0, 0.5, 0.1, -0.3, 0.3, False),
    (1.5, 4.0, 0.02, -0.7, 1.2, True),
    (0.8, -3.0, 0.05, -2.0, 0.5, True),
    (3.0, 10.0, 0.0, 0.0, 0.0, False),
]


def include_flags():
    return [flag for folder in sorted((ROOT / 'upstream_compat').glob('*/include')) + [ROOT / 'devel' / 'include']
            for flag in ('-I', str(folder))]


@pytest.fixture(scope='module')
def runner(tmp_path_factory):
    if shutil.which('g++') is None:
        pytest.skip('no C++ compiler')
    if not CONFIG_HEADER.is_file():
        pytest.fail('%s is missing: run `make build`' % CONFIG_HEADER)
    folder = tmp_path_factory.mktemp('pid_runner')
    (folder / 'runner.cpp').write_text(RUNNER)
    done = subprocess.run(['g++', '-std=c++17', '-O1'] + include_flags() +
                          [str(folder / 'runner.cpp'), '-o', str(folder / 'runner'),
                           '-lroscpp', '-lrostime', '-lrosconsole', '-lroscpp_serialization',
                           '-ldynamic_reconfigure_config_init_mutex', '-lboost_thread', '-lboost_system', '-lpthread'],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert done.returncode == 0, done.stdout

    def run(lines):
        out = subprocess.run([str(folder / 'runner')], input='\n'.join(lines) + '\n', capture_output=True,
                             text=True, timeout=60, check=True).stdout.split('\n')
        return [[float(v) for v in line.split()] for line in out if line and line != 'ok']
    return run


def gains_line(p, i, d, i_min, i_max, antiwindup):
    return 'gains %r %r %r %r %r %d' % (p, i, d, i_max, i_min, int(antiwindup))


@pytest.mark.parametrize('gains', GAINS, ids=['clamped_term', 'antiwindup', 'antiwindup_negative_i', 'no_clamp'])
def test_compute_command_matches_pid_py(runner, gains):
    """The same commands and errors, update by update, for a random mix of both computeCommand forms. reset(0, 0)
    starts the C++ Pid without a previous error, as pid.py starts (no derivative kick on the first update)."""
    rng = random.Random(hash(gains) & 0xffff)
    pid = Pid(*gains)
    lines = [gains_line(*gains), 'reset2 0 0']
    expected = []
    for _ in range(200):
        # as ros::Duration holds it: whole nanoseconds, toSec() = 1e-9 * nsec
        dt = 1e-9 * round(1e9 * rng.choice([0.001, 0.01, 0.02, rng.uniform(1e-4, 0.05)]))
        error = rng.uniform(-3.0, 3.0)
        if rng.random() < 0.2:
            error_dot = rng.uniform(-20.0, 20.0)
            lines.append('c3 %r %r %r' % (error, error_dot, dt))
            expected.append([pid.compute_with_error_dot(error, error_dot, dt)])
        else:
            lines.append('c2 %r %r' % (error, dt))
            expected.append([pid.compute(error, dt)])
        lines.append('errors')
        expected.append([pid.p_error, pid.i_error, pid.d_error])
    got = runner(lines)
    assert len(got) == len(expected)
    for step, (cpp, py) in enumerate(zip(got, expected)):
        assert cpp == pytest.approx(py, rel=1e-12, abs=1e-12), 'line %d: %s' % (step, lines[step + 2])


def test_upstream_kicks_the_derivative_on_the_first_update_after_reset(runner):
    """Upstream's reset() leaves a previous error of 0 to differentiate against (pid.py does not, on purpose)."""
    p, i, d, dt, error = 2.0, 0.0, 0.5, 0.01, 1.0
    got = runner([gains_line(p, i, d, 0.0, 0.0, False), 'reset', 'c2 %r %r' % (error, dt), 'c2 %r %r' % (error, dt)])
    assert got[0] == [pytest.approx(p * error + d * error / dt)]
    assert got[1] == [pytest.approx(p * error)]
    assert Pid(p, i, d).compute(error, dt) == pytest.approx(p * error)  # pid.py: no kick


def test_reset_with_errors_uses_the_given_derivative_first(runner):
    got = runner([gains_line(0.0, 1.0, 1.0, -10.0, 10.0, False), 'reset2 4 0.5', 'c2 1 0.1', 'errors'])
    assert got[0] == [pytest.approx(1.0 * (0.5 + 0.1 * 1.0) + 1.0 * 4.0)]
    assert got[1] == pytest.approx([1.0, 0.6, 4.0])


def test_zero_dt_and_non_finite_errors_give_zero_and_change_nothing(runner):
    got = runner([gains_line(2.0, 1.0, 0.1, -5.0, 5.0, False), 'reset2 0 0', 'c2 1 0.01', 'errors', 'cmd',
                  'c2 3 0', 'c2 nan 0.01', 'c2 inf 0.01', 'cmd', 'errors'])
    first, errors_before, cmd_before = got[0], got[1], got[2]
    assert got[3:6] == [[0.0], [0.0], [0.0]]
    assert got[6] == cmd_before == first
    assert got[7] == errors_before


def test_non_finite_error_dot_gives_zero_but_is_stored_as_upstream(runner):
    got = runner([gains_line(2.0, 1.0, 0.1, -5.0, 5.0, False), 'reset2 0 0', 'c3 1 inf 0.01', 'errors'])
    assert got[0] == [0.0]
    assert got[1][0] == 1.0 and got[1][1] == 0.0 and math.isinf(got[1][2])


def test_negative_dt_integrates_with_the_previous_derivative_as_upstream(runner):
    """Upstream only refuses dt == 0: a negative dt still integrates (pid.py returns 0 and changes nothing)."""
    p, i, d = 1.0, 2.0, 0.5
    got = runner([gains_line(p, i, d, -100.0, 100.0, False), 'reset2 0 0', 'c2 1 0.1', 'c2 2 0.1', 'c2 3 -0.1',
                  'errors'])
    # after the second update: i_error 0.3, d_error 10; the third integrates -0.3 and keeps d_error
    assert got[2] == [pytest.approx(p * 3.0 + i * 0.0 + d * 10.0)]
    assert got[3] == pytest.approx([3.0, 0.0, 10.0], abs=1e-12)
    assert Pid(p, i, d, -100.0, 100.0).compute(3.0, -0.1) == 0.0

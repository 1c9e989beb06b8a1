"""racebot's C++ API of control_toolbox (Pid) and joint_limits_interface (upstream_compat/*/include): every header
compiles in a translation unit using its main calls, as C++11 (what AgileX hunter's steer_bot_hardware_gazebo asks
for) and C++17, against the stand-ins' include folders and the devel space (ParametersConfig.h, control_msgs); and the
joint limits handles enforce ros_control 0.20's rules, the effort saturation the same as racebot_sim_bridge's Python
RobotHW (hardware_interface.py, limited_command). Needs `make build` and g++; no master.
"""
import shutil
import subprocess
from pathlib import Path

import pytest

from racebot_sim_bridge.ros_control.hardware_interface import EFFORT, JointHandle

ROOT = Path(__file__).resolve().parents[3]
DEVEL_INCLUDE = ROOT / 'devel' / 'include'

pytestmark = pytest.mark.skipif(shutil.which('g++') is None, reason='no C++ compiler')

EVERY_HEADER = r'''
#include <control_toolbox/pid.h>
#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>
#include <joint_limits_interface/joint_limits_rosparam.h>
#include <joint_limits_interface/joint_limits_urdf.h>
#include <tinyxml.h>
#include <urdf/model.h>
#include <vector>

using namespace joint_limits_interface;

void pid_calls(const ros::NodeHandle& nh, TiXmlElement* xml)
{
  control_toolbox::Pid pid(1.0, 0.5, 0.1, 1.0, -1.0, true);
  std::vector<control_toolbox::Pid> pids;
  pids.resize(3);  // copies, as a RobotHWSim's vector of Pids does
  pid = pids[0];
  bool ok = pid.init(nh) && pid.init(nh, true) && pid.initParam("pid") && pid.initXml(xml);
  pid.initPid(1.0, 2.0, 3.0, 4.0, -4.0);
  pid.initPid(1.0, 2.0, 3.0, 4.0, -4.0, true, nh);
  double p, i, d, i_max, i_min, pe, ie, de;
  bool antiwindup;
  pid.getGains(p, i, d, i_max, i_min);
  pid.getGains(p, i, d, i_max, i_min, antiwindup);
  control_toolbox::Pid::Gains gains = pid.getGains();
  pid.setGains(gains);
  pid.setGains(p, i, d, i_max, i_min, ok);
  ros::NodeHandle node(nh);
  pid.initDynamicReconfig(node);
  double cmd = pid.computeCommand(0.1, ros::Duration(0.01)) + pid.computeCommand(0.1, 0.2, ros::Duration(0.01));
  pid.setCurrentCmd(cmd);
  cmd = pid.getCurrentCmd();
  pid.getCurrentPIDErrors(&pe, &ie, &de);
  pid.printValues();
  pid.reset();
  pid.reset(0.0, 1.0);
}

void limits_calls(const ros::NodeHandle& nh, const urdf::Model& model, hardware_interface::JointHandle jh)
{
  JointLimits limits;
  SoftJointLimits soft;
  urdf::JointConstSharedPtr joint = model.getJoint("j");
  bool ok = getJointLimits(joint, limits) && getSoftJointLimits(joint, soft) && getJointLimits("j", nh, limits) &&
            getSoftJointLimits("j", nh, soft);
  const ros::Duration period(0.01);
  PositionJointSaturationInterface a;
  a.registerHandle(PositionJointSaturationHandle(jh, limits));
  a.enforceLimits(period);
  a.reset();
  PositionJointSoftLimitsInterface b;
  b.registerHandle(PositionJointSoftLimitsHandle(jh, limits, soft));
  b.getHandle("j").enforceLimits(period);
  b.reset();
  EffortJointSaturationInterface c;
  c.registerHandle(EffortJointSaturationHandle(jh, limits));
  c.enforceLimits(period);
  EffortJointSoftLimitsInterface e;
  e.registerHandle(EffortJointSoftLimitsHandle(jh, limits, soft));
  e.enforceLimits(period);
  VelocityJointSaturationInterface f;
  f.registerHandle(VelocityJointSaturationHandle(jh, limits));
  f.enforceLimits(period);
  VelocityJointSoftLimitsInterface g;
  g.registerHandle(VelocityJointSoftLimitsHandle(jh, limits, soft));
  g.enforceLimits(period);
  std::vector<std::string> names = g.getNames();
  try
  {
    g.getHandle("missing");
  }
  catch (const JointLimitsInterfaceException& ex)
  {
    ok = ok && ex.what() != nullptr && !names.empty();
  }
}
'''

# Each scenario prints one line of results.
LIMITS_RUNNER = r'''
#include <joint_limits_interface/joint_limits_interface.h>
#include <cstdio>

using namespace joint_limits_interface;

int main()
{
  double pos = 0.0, vel = 0.0, eff = 0.0, cmd = 0.0;
  hardware_interface::JointHandle jh(hardware_interface::JointStateHandle("j", &pos, &vel, &eff), &cmd);
  const ros::Duration period(0.1);

  JointLimits limits;
  limits.has_position_limits = true;
  limits.min_position = -1.0;
  limits.max_position = 1.0;
  limits.has_velocity_limits = true;
  limits.max_velocity = 2.0;
  limits.has_effort_limits = true;
  limits.max_effort = 10.0;

  // effort saturation: (position, velocity, command) triples from stdin
  EffortJointSaturationHandle effort(jh, limits);
  while (std::scanf("%lf %lf %lf", &pos, &vel, &cmd) == 3)
  {
    effort.enforceLimits(period);
    std::printf("%.17g\n", cmd);
  }

  // position saturation: from the joint's position at 0.5, 0.2 a step (2 rad/s * 0.1 s), never past 1
  pos = 0.5;
  PositionJointSaturationHandle position(jh, limits);
  for (double target : {3.0, 3.0, 3.0, -3.0})
  {
    cmd = target;
    position.enforceLimits(period);
    std::printf("%.17g ", cmd);
  }
  position.reset();
  pos = -0.95;
  cmd = -3.0;
  position.enforceLimits(period);
  std::printf("%.17g\n", cmd);

  // position soft limits at +-0.5, k_position 10: from 0.4 it may go up at 10 * (0.5 - 0.4) = 1 rad/s, 0.1 in 0.1 s
  SoftJointLimits soft;
  soft.min_position = -0.5;
  soft.max_position = 0.5;
  soft.k_position = 10.0;
  soft.k_velocity = 5.0;
  pos = 0.4;
  PositionJointSoftLimitsHandle soft_position(jh, limits, soft);
  cmd = 3.0;
  soft_position.enforceLimits(period);
  std::printf("%.17g ", cmd);
  cmd = -3.0;  // downwards, from the previous command 0.5, only the velocity limit holds it: 2 rad/s * 0.1 s
  soft_position.enforceLimits(period);
  std::printf("%.17g\n", cmd);

  // velocity saturation with an acceleration limit of 5: 0.5 a step from the previous command (0 at first)
  limits.has_acceleration_limits = true;
  limits.max_acceleration = 5.0;
  VelocityJointSaturationHandle velocity(jh, limits);
  for (double target : {3.0, 3.0, 3.0, 3.0, 3.0, -1.0})
  {
    cmd = target;
    velocity.enforceLimits(period);
    std::printf("%.17g ", cmd);
  }
  std::printf("\n");

  // the handles that need limits refuse a joint without them
  JointLimits none;
  int refused = 0;
  try { EffortJointSaturationHandle(jh, none); } catch (const JointLimitsInterfaceException&) { ++refused; }
  try { PositionJointSoftLimitsHandle(jh, none, soft); } catch (const JointLimitsInterfaceException&) { ++refused; }
  try { VelocityJointSaturationHandle(jh, none); } catch (const JointLimitsInterfaceException&) { ++refused; }
  EffortJointSaturationInterface interface;
  try { interface.getHandle("j"); } catch (const JointLimitsInterfaceException&) { ++refused; }
  std::printf("%d\n", refused);
  return 0;
}
'''


def include_flags():
    return [flag for folder in sorted((ROOT / 'upstream_compat').glob('*/include')) + [DEVEL_INCLUDE]
            for flag in ('-I', str(folder))]


def require_build():
    if not (DEVEL_INCLUDE / 'control_toolbox' / 'ParametersConfig.h').is_file():
        pytest.fail('the devel space has no control_toolbox/ParametersConfig.h: run `make build`')


@pytest.mark.parametrize('standard', ['c++11', 'c++17'])
def test_every_header_compiles_with_its_main_calls(tmp_path, standard):
    require_build()
    source = tmp_path / 'every_header.cpp'
    source.write_text(EVERY_HEADER)
    done = subprocess.run(['g++', '-std=' + standard, '-fsyntax-only', '-Wall', '-Wno-deprecated-declarations'] +
                          include_flags() + [str(source)],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert done.returncode == 0, done.stdout


EFFORT_CASES = [  # position, velocity, command
    (0.0, 0.0, 4.0), (0.0, 0.0, 25.0), (0.0, 0.0, -25.0),
    (1.2, 0.0, 5.0), (1.2, 0.0, -5.0), (-1.2, 0.0, -5.0), (-1.2, 0.0, 5.0),
    (0.0, 2.5, 5.0), (0.0, 2.5, -5.0), (0.0, -2.5, -5.0), (0.0, -2.5, 5.0), (1.2, -2.5, 50.0),
]


def test_joint_limits_handles_enforce_ros_controls_rules(tmp_path):
    require_build()
    source = tmp_path / 'limits.cpp'
    source.write_text(LIMITS_RUNNER)
    done = subprocess.run(['g++', '-std=c++17'] + include_flags() + [str(source), '-o', str(tmp_path / 'limits'),
                                                                    '-lrostime', '-lrosconsole', '-lroscpp'],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert done.returncode == 0, done.stdout
    stdin = ''.join('%r %r %r\n' % case for case in EFFORT_CASES)
    lines = subprocess.run([str(tmp_path / 'limits')], input=stdin, stdout=subprocess.PIPE, text=True, timeout=60,
                           check=True).stdout.splitlines()
    efforts = [float(line) for line in lines[:len(EFFORT_CASES)]]
    position, soft_position, velocity, refused = lines[len(EFFORT_CASES):]

    # effort: +-10, and none pushing further past a position or velocity limit; racebot's Python RobotHW agrees
    assert efforts == [4.0, 10.0, -10.0, 0.0, -5.0, 0.0, 5.0, 0.0, -5.0, 0.0, 5.0, 0.0]
    for (pos, vel, cmd), limited in zip(EFFORT_CASES, efforts):
        joint = JointHandle('j', 'revolute', EFFORT, -1.0, 1.0, 10.0, 2.0)
        joint.position, joint.velocity, joint.command = pos, vel, cmd
        assert joint.limited_command() == limited, (pos, vel, cmd)

    assert [float(v) for v in position.split()] == pytest.approx([0.7, 0.9, 1.0, 0.8, -1.0])
    assert [float(v) for v in soft_position.split()] == pytest.approx([0.5, 0.3])
    assert [float(v) for v in velocity.split()] == pytest.approx([0.5, 1.0, 1.5, 2.0, 2.0, 1.5])
    assert refused == '4'

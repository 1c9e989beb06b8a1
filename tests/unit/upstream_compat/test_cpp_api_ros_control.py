"""racebot's C++ API of ros_control for controllers (upstream_compat/{hardware_interface,controller_interface,
realtime_tools,gazebo_ros_control,transmission_interface}/include): every header compiles in a translation unit
using its main calls, as C++11 (packages still write add_compile_options(-std=c++11)) and C++17; and a program built
on them behaves as ros_control 0.20 does: claims, interfaces combined across nested RobotHWs, a Controller's and a
MultiInterfaceController's initRequest and claimed resources, the state machine, RealtimeBuffer. Needs g++ and
Debian's roscpp; no master (ros::init without one: only roscpp's own logger services ask for it, and give up).
"""
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
HEADERS = ('hardware_interface', 'controller_interface', 'realtime_tools')

pytestmark = pytest.mark.skipif(shutil.which('g++') is None, reason='no C++ compiler')

PROGRAM = r'''
#include <controller_interface/controller.h>
#include <controller_interface/multi_interface_controller.h>
#include <hardware_interface/force_torque_sensor_interface.h>
#include <hardware_interface/imu_sensor_interface.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <realtime_tools/realtime_box.h>
#include <realtime_tools/realtime_buffer.h>
#include <realtime_tools/realtime_publisher.h>
#include <std_msgs/Float64.h>
#include <cstdio>
#include <list>
#include <string>

using namespace hardware_interface;

struct Velocity : controller_interface::Controller<VelocityJointInterface>
{
  bool init(VelocityJointInterface* hw, ros::NodeHandle&) override
  {
    joint = hw->getHandle("wheel");
    return true;
  }
  void starting(const ros::Time&) override { joint.setCommand(0.0); }
  void update(const ros::Time&, const ros::Duration&) override { joint.setCommand(*command.readFromRT()); }
  JointHandle joint;
  realtime_tools::RealtimeBuffer<double> command{0.0};
};

struct Hold : controller_interface::MultiInterfaceController<EffortJointInterface, JointStateInterface,
                                                              PositionJointInterface>
{
  Hold() : controller_interface::MultiInterfaceController<EffortJointInterface, JointStateInterface,
                                                          PositionJointInterface>(true) {}
  bool init(RobotHW* hw, ros::NodeHandle&) override
  {
    position_missing = hw->get<PositionJointInterface>() == nullptr;
    arm = hw->get<EffortJointInterface>()->getHandle("arm");
    watched = hw->get<JointStateInterface>()->getHandle("wheel");
    return true;
  }
  void update(const ros::Time&, const ros::Duration&) override { arm.setCommand(-watched.getPosition()); }
  bool position_missing = false;
  JointHandle arm;
  JointStateHandle watched;
};

struct Needs : controller_interface::MultiInterfaceController<EffortJointInterface, PositionJointInterface>
{
  void update(const ros::Time&, const ros::Duration&) override {}
};

// as the controller manager calls it: through the base, where it is public
static bool init(controller_interface::ControllerBase& c, RobotHW* hw, ros::NodeHandle& nh,
                 controller_interface::ControllerBase::ClaimedResources& claimed)
{
  return c.initRequest(hw, nh, nh, claimed);
}

static void print_claims(const char* who, const controller_interface::ControllerBase::ClaimedResources& claimed)
{
  for (const auto& c : claimed)
  {
    std::printf("probe %s %s:", who, c.hardware_interface.c_str());
    for (const auto& r : c.resources)
      std::printf(" %s", r.c_str());
    std::printf("\n");
  }
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "cpp_api_probe", ros::init_options::NoRosout | ros::init_options::NoSigintHandler);
  ros::master::setRetryTimeout(ros::WallDuration(0.2));  // no master: roscpp's own services give up at once
  ros::NodeHandle nh;

  // two RobotHWs nested in one: the state interfaces combined, each command interface from its own
  double pos[2] = {0.5, -0.25}, vel[2] = {0, 0}, eff[2] = {0, 0}, cmd[2] = {0, 0};
  RobotHW wheels, arms, robot;
  JointStateInterface wheel_states, arm_states;
  VelocityJointInterface velocity;
  EffortJointInterface effort;
  JointStateHandle wheel("wheel", &pos[0], &vel[0], &eff[0]), arm("arm", &pos[1], &vel[1], &eff[1]);
  wheel_states.registerHandle(wheel);
  arm_states.registerHandle(arm);
  velocity.registerHandle(JointHandle(wheel, &cmd[0]));
  effort.registerHandle(JointHandle(arm, &cmd[1]));
  wheels.registerInterface(&wheel_states);
  wheels.registerInterface(&velocity);
  arms.registerInterface(&arm_states);
  arms.registerInterface(&effort);
  robot.registerInterfaceManager(&wheels);
  robot.registerInterfaceManager(&arms);
  std::printf("probe combined states: %zu\n", robot.get<JointStateInterface>()->getNames().size());
  std::printf("probe same combination: %d\n", robot.get<JointStateInterface>() == robot.get<JointStateInterface>());
  std::printf("probe interfaces: %zu\n", robot.getNames().size());
  try
  {
    robot.get<VelocityJointInterface>()->getHandle("arm");
  }
  catch (const HardwareInterfaceException& e)
  {
    std::printf("probe refused: %s\n", e.what());
  }

  Velocity v;
  controller_interface::ControllerBase::ClaimedResources claimed;
  std::printf("probe start before init: %d\n", v.startRequest(ros::Time(0)));
  const bool v_ok = init(v, &robot, nh, claimed);
  std::printf("probe velocity init: %d initialized %d\n", v_ok, v.isInitialized());
  print_claims("velocity", claimed);
  Hold h;
  const bool h_ok = init(h, &robot, nh, claimed);
  std::printf("probe hold init: %d position missing %d\n", h_ok, h.position_missing);
  print_claims("hold", claimed);
  Needs n;
  std::printf("probe needs init: %d\n", init(n, &robot, nh, claimed));

  v.command.writeFromNonRT(3.0);
  v.updateRequest(ros::Time(1), ros::Duration(0.001));  // not running: nothing
  std::printf("probe cmd before start: %g\n", cmd[0]);
  v.startRequest(ros::Time(1));
  h.startRequest(ros::Time(1));
  v.updateRequest(ros::Time(1), ros::Duration(0.001));
  h.updateRequest(ros::Time(1), ros::Duration(0.001));
  std::printf("probe running %d cmd %g %g\n", v.isRunning(), cmd[0], cmd[1]);
  v.stopRequest(ros::Time(2));
  std::printf("probe stopped %d\n", v.isStopped());

  std::list<ControllerInfo> infos(2);
  infos.front().name = "a";
  infos.front().claimed_resources.push_back(InterfaceResources("x", {"wheel"}));
  infos.back().name = "b";
  infos.back().claimed_resources.push_back(InterfaceResources("y", {"wheel"}));
  std::printf("probe conflict: %d\n", robot.checkForConflict(infos));

  double quaternion[4] = {0, 0, 0, 1}, force[3] = {1, 2, 3};
  ImuSensorHandle::Data imu_data;
  imu_data.name = "imu";
  imu_data.frame_id = "imu_link";
  imu_data.orientation = quaternion;
  ImuSensorInterface imus;
  imus.registerHandle(ImuSensorHandle(imu_data));
  ForceTorqueSensorInterface wrenches;
  wrenches.registerHandle(ForceTorqueSensorHandle("wrist", "wrist_link", force, force));
  robot.registerInterface(&imus);
  robot.registerInterface(&wrenches);
  ImuSensorHandle imu = robot.get<ImuSensorInterface>()->getHandle("imu");
  std::printf("probe imu %s w %g accel %d\n", imu.getFrameId().c_str(), imu.getOrientation()[3],
              imu.getLinearAcceleration() == nullptr);
  std::printf("probe wrench %g\n", robot.get<ForceTorqueSensorInterface>()->getHandle("wrist").getForce()[2]);

  realtime_tools::RealtimeBox<int> box(4);
  int boxed = 0;
  box.get(boxed);
  std::printf("probe box %d\n", boxed);
  return 0;
}
'''

EXPECTED = [
    'combined states: 2',
    'same combination: 1',
    'interfaces: 3',
    "refused: Could not find resource 'arm' in 'hardware_interface::VelocityJointInterface'.",
    'start before init: 0',
    'velocity init: 1 initialized 1',
    'velocity hardware_interface::VelocityJointInterface: wheel',
    'hold init: 1 position missing 1',
    'hold hardware_interface::EffortJointInterface: arm',
    'hold hardware_interface::JointStateInterface:',
    'needs init: 0',
    'cmd before start: 0',
    'running 1 cmd 3 -0.5',
    'stopped 1',
    'conflict: 1',
    'imu imu_link w 1 accel 1',
    'wrench 3',
    'box 4',
]


def include_flags():
    return [flag for name in HEADERS for flag in ('-I', str(ROOT / 'upstream_compat' / name / 'include'))] + \
        ['-I', str(ROOT / 'upstream_compat' / 'roscpp' / 'include' / 'boost_global_placeholders')]


def roscpp_flags():
    done = subprocess.run(['pkg-config', '--cflags', '--libs', 'roscpp'], stdout=subprocess.PIPE, text=True)
    if done.returncode != 0:
        pytest.fail("pkg-config knows no roscpp: run 'make setup' (Debian's libroscpp-dev)")
    return done.stdout.split()


@pytest.mark.parametrize('standard', ['c++11', 'c++17'])
def test_the_controller_api_builds_and_behaves_as_ros_controls(tmp_path, standard):
    source, program = tmp_path / 'probe.cpp', tmp_path / 'probe'
    source.write_text(PROGRAM)
    built = subprocess.run(['g++', '-std=' + standard, '-Wall', '-o', str(program), str(source)] + include_flags() +
                           roscpp_flags(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert built.returncode == 0, built.stdout
    ran = subprocess.run([str(program)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=60,
                         env={'ROS_MASTER_URI': 'http://localhost:1', 'PATH': '/usr/bin:/bin'})
    lines = [line[len('probe '):] for line in ran.stdout.splitlines() if line.startswith('probe ')]
    assert ran.returncode == 0, ran.stdout
    assert lines == EXPECTED, ran.stdout


def test_robot_hw_sim_and_transmission_info_headers_compile(tmp_path):
    source = tmp_path / 'sim.cpp'
    source.write_text('#include <gazebo_ros_control/robot_hw_sim.h>\n'
                      'struct S : gazebo_ros_control::RobotHWSim {\n'
                      '  bool initSim(const std::string&, ros::NodeHandle, gazebo::physics::ModelPtr,\n'
                      '               const urdf::Model* const,\n'
                      '               std::vector<transmission_interface::TransmissionInfo> t)\n'
                      '  override { return !t.empty() && t[0].joints_[0].role_.empty(); }\n'
                      '  void readSim(ros::Time, ros::Duration) override {}\n'
                      '  void writeSim(ros::Time, ros::Duration) override {}\n'
                      '};\n')
    flags = include_flags() + [flag for name in ('gazebo_ros_control', 'transmission_interface', 'gazebo_dev')
                               for flag in ('-I', str(ROOT / 'upstream_compat' / name / 'include'))]
    folders = ['/usr/include/ignition/math6', '/usr/include/ignition/common4', '/usr/include/ignition/utils1']
    folders += [str(p) for p in Path('/usr/include').glob('sdformat-12*')]
    flags += [flag for folder in folders for flag in ('-I', folder)]
    done = subprocess.run(['g++', '-std=c++17', '-fsyntax-only', str(source)] + flags + roscpp_flags(),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert done.returncode == 0, done.stdout

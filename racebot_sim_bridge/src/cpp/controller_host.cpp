// racebot's host of compiled ros_control controllers: a controller `type` the Python controller manager has no
// class for is made through pluginlib (base controller_interface::ControllerBase, as controller_manager's loader),
// initialized on a RobotHW whose handles are the simulated joints', and driven by the Python manager in its update
// order beside the Python controllers.
//
// The RobotHW (SimRobotHW) registers what gazebo_ros_control's DefaultRobotHWSim does: every joint in the joint
// state interface and in the command interface of its transmission. Its storage is a copy of the Python joint
// handles (racebot_sim_bridge.ros_control.hardware_interface.JointHandle): each call into a controller reads
// position, velocity, effort and command from them first, and writes back afterwards the commands of the joints
// that controller claimed (a resource is claimed by one running controller at a time: ros_control's rule, which
// the Python manager checks), so Python and C++ controllers share the joints within one update.
//
// Controller code runs without the interpreter lock; it publishes and subscribes with roscpp, which runs in the
// world server (gazebo_host's start_roscpp). Built by racebot_sim_bridge/CMakeLists.txt into the devel space's
// ros_control folder.
#include <signal.h>
#include <string.h>
#include <unistd.h>

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <ros/ros.h>

#include <controller_interface/controller_base.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <pluginlib/class_loader.hpp>

namespace py = pybind11;

namespace
{
const char kEffort[] = "hardware_interface/EffortJointInterface";
const char kVelocity[] = "hardware_interface/VelocityJointInterface";
const char kPosition[] = "hardware_interface/PositionJointInterface";

// A crash inside a controller's code ends the world server, as it ends gzserver, but the log says which controller
// was running (its init, starting, update or stopping), then the signal goes on to the handler before this one.
namespace crash
{
constexpr int kLabel = 200;
char running[kLabel];  // empty when no controller code runs on the simulation thread
const int kSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
struct sigaction previous[sizeof(kSignals) / sizeof(kSignals[0])];
bool installed = false;

void Say(const char* text) { (void)!write(STDERR_FILENO, text, strlen(text)); }

void Handler(int signal, siginfo_t*, void*)
{
  if (running[0])
  {
    Say("\nracebot: the world server crashed inside compiled ros_control controller ");
    Say(running);
    Say(", in its own code: fix or rebuild that controller, or leave it out of the controllers you spawn\n");
  }
  for (size_t i = 0; i < sizeof(kSignals) / sizeof(kSignals[0]); ++i)
    if (kSignals[i] == signal)
      sigaction(signal, &previous[i], nullptr);
  raise(signal);
}

void Install()
{
  if (installed)
    return;
  installed = true;
  struct sigaction action;
  memset(&action, 0, sizeof(action));
  action.sa_sigaction = Handler;
  action.sa_flags = SA_SIGINFO | SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  for (size_t i = 0; i < sizeof(kSignals) / sizeof(kSignals[0]); ++i)
    sigaction(kSignals[i], &action, &previous[i]);
}

// Names the controller while it runs.
class Running
{
public:
  explicit Running(const std::string& label)
  {
    strncpy(running, label.c_str(), kLabel - 1);
    running[kLabel - 1] = '\0';
  }
  ~Running() { running[0] = '\0'; }
};
}  // namespace crash

// gazebo_ros_control's DefaultRobotHWSim as ros_control's C++ controllers see it.
class SimRobotHW : public hardware_interface::RobotHW
{
public:
  // joints: (name, interface) in the Python handles' order; storage is sized once, so handles' pointers hold.
  explicit SimRobotHW(const std::vector<std::pair<std::string, std::string>>& joints)
    : pos(joints.size()), vel(joints.size()), eff(joints.size()), cmd(joints.size())
  {
    for (size_t i = 0; i < joints.size(); ++i)
    {
      const std::string& name = joints[i].first;
      const std::string& interface = joints[i].second;
      hardware_interface::JointStateHandle state(name, &pos[i], &vel[i], &eff[i]);
      this->state.registerHandle(state);
      hardware_interface::JointHandle command(state, &cmd[i]);
      if (interface == kEffort)
        this->effort.registerHandle(command);
      else if (interface == kVelocity)
        this->velocity.registerHandle(command);
      else if (interface == kPosition)
        this->position.registerHandle(command);
      index[name] = i;
    }
    registerInterface(&this->state);
    registerInterface(&this->effort);
    registerInterface(&this->position);
    registerInterface(&this->velocity);
  }

  std::vector<double> pos, vel, eff, cmd;
  std::map<std::string, size_t> index;

private:
  hardware_interface::JointStateInterface state;
  hardware_interface::EffortJointInterface effort;
  hardware_interface::PositionJointInterface position;
  hardware_interface::VelocityJointInterface velocity;
};

typedef pluginlib::ClassLoader<controller_interface::ControllerBase> Loader;

// One process-wide loader (it asks rospack for every package's exported controllers once), kept while a Host is.
std::shared_ptr<Loader> SharedLoader()
{
  static std::weak_ptr<Loader> shared;
  std::shared_ptr<Loader> loader = shared.lock();
  if (!loader)
  {
    loader = std::make_shared<Loader>("controller_interface", "controller_interface::ControllerBase");
    shared = loader;
  }
  return loader;
}

struct Loaded
{
  std::string name, type, label;
  controller_interface::ControllerBase::ClaimedResources claimed;
  std::vector<size_t> commanded;  // the joints whose commands it claimed, by index
  std::shared_ptr<controller_interface::ControllerBase> controller;
};

// The C++ controllers of one controller manager, on one robot's joints.
class Host
{
public:
  // joints: (name, interface, Python JointHandle) for every joint of the robot's RobotHWSim.
  Host(const std::string& ns, const std::vector<std::tuple<std::string, std::string, py::object>>& joints)
    : ns(ns), loader(SharedLoader())
  {
    std::vector<std::pair<std::string, std::string>> described;
    for (const auto& joint : joints)
    {
      described.emplace_back(std::get<0>(joint), std::get<1>(joint));
      handles.push_back(std::get<2>(joint));
    }
    hw.reset(new SimRobotHW(described));
    crash::Install();
  }

  ~Host()
  {
    py::gil_scoped_release release;
    controllers.clear();  // before the loader that holds their libraries
  }

  bool Available(const std::string& type)
  {
    py::gil_scoped_release release;
    return loader->isClassAvailable(type);
  }

  // Declared and its library found: what a package built, not a name in racebot's own plugin XMLs.
  bool Built(const std::string& type)
  {
    py::gil_scoped_release release;
    if (!loader->isClassAvailable(type))
      return false;
    try
    {
      return !loader->getClassLibraryPath(type).empty();
    }
    catch (const pluginlib::PluginlibException&)
    {
      return false;
    }
  }

  std::vector<std::string> Types()
  {
    py::gil_scoped_release release;
    return loader->getDeclaredClasses();
  }

  // Makes and initializes the controller; its id. std::runtime_error saying why when it cannot.
  int Load(const std::string& name, const std::string& type)
  {
    auto made = std::make_shared<Loaded>();
    made->name = name;
    made->type = type;
    made->label = "'" + name + "' (" + type + ")";
    {
      py::gil_scoped_release release;
      try
      {
        made->controller = loader->createSharedInstance(type);
      }
      catch (const pluginlib::PluginlibException& error)
      {
        throw std::runtime_error("pluginlib could not make a " + type + ": " + error.what());
      }
      ros::NodeHandle root(ns.empty() ? "/" : ns);
      ros::NodeHandle own(root, name);
      bool ok = false;
      try
      {
        crash::Running running(made->label);
        ok = made->controller->initRequest(hw.get(), root, own, made->claimed);
      }
      catch (const std::exception& error)
      {
        throw std::runtime_error(std::string("its init threw: ") + error.what());
      }
      if (!ok)
        throw std::runtime_error("its init returned false (the controller's own error is in the world server's "
                                 "log, from its roscpp node)");
    }
    for (const auto& claimed : made->claimed)
      if (claimed.hardware_interface != "hardware_interface::JointStateInterface")
        for (const std::string& resource : claimed.resources)
        {
          auto found = hw->index.find(resource);
          if (found != hw->index.end())
            made->commanded.push_back(found->second);
        }
    const int id = ++last_id;
    controllers[id] = made;
    return id;
  }

  // [(interface, [resources])] as list_controllers reports them.
  std::vector<std::pair<std::string, std::vector<std::string>>> Claimed(int id)
  {
    std::vector<std::pair<std::string, std::vector<std::string>>> out;
    for (const auto& claimed : Get(id).claimed)
      out.emplace_back(claimed.hardware_interface,
                       std::vector<std::string>(claimed.resources.begin(), claimed.resources.end()));
    return out;
  }

  void Starting(int id, double time) { Call(id, [time](controller_interface::ControllerBase& c) { c.startRequest(ros::Time(time)); }); }
  void Stopping(int id, double time) { Call(id, [time](controller_interface::ControllerBase& c) { c.stopRequest(ros::Time(time)); }); }
  void Update(int id, double time, double period)
  {
    Call(id, [time, period](controller_interface::ControllerBase& c) {
      c.updateRequest(ros::Time(time), ros::Duration(period));
    });
  }

  void Unload(int id)
  {
    std::shared_ptr<Loaded> gone = controllers.at(id);
    controllers.erase(id);
    py::gil_scoped_release release;
    gone.reset();  // its destructor may shut down publishers: roscpp calls, without the lock
  }

private:
  Loaded& Get(int id)
  {
    auto found = controllers.find(id);
    if (found == controllers.end())
      throw std::out_of_range("no compiled controller " + std::to_string(id));
    return *found->second;
  }

  // The joints' state and commands from the Python handles.
  void Read()
  {
    static const py::str position("position"), velocity("velocity"), effort("effort"), command("command");
    for (size_t i = 0; i < handles.size(); ++i)
    {
      const py::handle h = handles[i];
      hw->pos[i] = h.attr(position).cast<double>();
      hw->vel[i] = h.attr(velocity).cast<double>();
      hw->eff[i] = h.attr(effort).cast<double>();
      hw->cmd[i] = h.attr(command).cast<double>();
    }
  }

  template <class F>
  void Call(int id, F call)
  {
    Loaded& loaded = Get(id);
    Read();
    {
      py::gil_scoped_release release;
      crash::Running running(loaded.label);
      try
      {
        call(*loaded.controller);
      }
      catch (const std::exception& error)
      {
        throw std::runtime_error(std::string("C++ exception: ") + error.what());
      }
    }
    static const py::str command("command");
    for (size_t i : loaded.commanded)
      handles[i].attr(command) = hw->cmd[i];
  }

  std::string ns;
  std::shared_ptr<Loader> loader;
  std::unique_ptr<SimRobotHW> hw;
  std::vector<py::object> handles;
  std::map<int, std::shared_ptr<Loaded>> controllers;
  int last_id = 0;
};
}  // namespace

PYBIND11_MODULE(controller_host, m)
{
  m.doc() = "racebot's host of compiled ros_control controllers (racebot_sim_bridge/src/cpp/controller_host.cpp)";
  py::class_<Host>(m, "Host")
    .def(py::init<const std::string&, const std::vector<std::tuple<std::string, std::string, py::object>>&>(),
         py::arg("ns"), py::arg("joints"))
    .def("available", &Host::Available, py::arg("type"))
    .def("built", &Host::Built, py::arg("type"))
    .def("types", &Host::Types)
    .def("load", &Host::Load, py::arg("name"), py::arg("type"))
    .def("claimed", &Host::Claimed, py::arg("id"))
    .def("starting", &Host::Starting, py::arg("id"), py::arg("time"))
    .def("stopping", &Host::Stopping, py::arg("id"), py::arg("time"))
    .def("update", &Host::Update, py::arg("id"), py::arg("time"), py::arg("period"))
    .def("unload", &Host::Unload, py::arg("id"));
}

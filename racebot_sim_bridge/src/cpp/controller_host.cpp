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
// With a package's own RobotHWSim (gazebo_ros_control's <robotSimType>), the RobotHW is that class instead, made through
// pluginlib and initialized with the model (racebot's Gazebo 11 plugin API, from gazebo_host), its URDF and
// transmissions; readSim and writeSim run around the controllers. The C++ controllers then use its handles directly,
// and the Python controllers (joint_state_controller, ...) a mirror of them: Python joint handles that readSim's
// states are copied into, and whose commands are copied back before writeSim for the joints no running C++
// controller claimed.
//
// Controller code runs without the interpreter lock; it publishes and subscribes with roscpp, which runs in the
// world server (gazebo_host's start_roscpp). Built by racebot_sim_bridge/CMakeLists.txt into the devel space's
// ros_control folder.
#include <string.h>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
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
#include <gazebo_ros_control/robot_hw_sim.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <pluginlib/class_loader.hpp>
#include <racebot_sim_bridge/fatal_signals.h>
#include <tinyxml.h>
#include <urdf/model.h>

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
racebot::fatal_signals::Chain chain;

void Handler(int signal, siginfo_t*, void*)
{
  if (running[0])
  {
    racebot::fatal_signals::Say("\nracebot: the world server crashed (");
    racebot::fatal_signals::Say(racebot::fatal_signals::Name(signal));
    racebot::fatal_signals::Say(") inside compiled ros_control controller ");
    racebot::fatal_signals::Say(running);
    racebot::fatal_signals::Say(", in its own code: fix or rebuild that controller, or leave it out of the "
                                "controllers you spawn\n");
  }
  chain.PassOn(signal);
}

void Install() { chain.Install(Handler); }

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
typedef pluginlib::ClassLoader<gazebo_ros_control::RobotHWSim> SimLoader;

// One process-wide loader per base class (each asks rospack for every package's exported classes once), kept while
// a Host is.
template <class L>
std::shared_ptr<L> Shared(const char* package, const char* base)
{
  static std::mutex guard;  // called without the interpreter lock, from the services' threads too
  static std::weak_ptr<L> shared;
  std::lock_guard<std::mutex> lock(guard);
  std::shared_ptr<L> loader = shared.lock();
  if (!loader)
  {
    loader = std::make_shared<L>(package, base);
    shared = loader;
  }
  return loader;
}

const char* const kCommandInterfaces[] = {kEffort, kVelocity, kPosition};

// The joint handles of a RobotHWSim's command interface `name` ('hardware_interface/EffortJointInterface', ...).
hardware_interface::JointCommandInterface* CommandInterface(hardware_interface::RobotHW& hw, const std::string& name)
{
  if (name == kEffort)
    return hw.get<hardware_interface::EffortJointInterface>();
  if (name == kVelocity)
    return hw.get<hardware_interface::VelocityJointInterface>();
  if (name == kPosition)
    return hw.get<hardware_interface::PositionJointInterface>();
  return nullptr;
}

// One joint of a RobotHWSim as the Python controllers see it.
struct Mirrored
{
  hardware_interface::JointStateHandle state;
  hardware_interface::JointHandle command;  // default (no command) for a joint with only a state
  bool commanded = false;
  py::object handle;
};

// The <hardwareInterface>s of a transmission's <joint> or <actuator>, as written.
std::vector<std::string> Interfaces(const TiXmlElement* element)
{
  std::vector<std::string> interfaces;
  for (const TiXmlElement* i = element->FirstChildElement("hardwareInterface"); i;
       i = i->NextSiblingElement("hardwareInterface"))
    if (i->GetText())
      interfaces.push_back(i->GetText());
  return interfaces;
}

std::string Text(const TiXmlElement* element)
{
  TiXmlPrinter printer;
  element->Accept(&printer);
  return printer.CStr();
}

// A URDF's <transmission>s as transmission_interface's TransmissionParser reads them for gazebo_ros_control: one
// without a name or a <type>, or a joint without a name or a <hardwareInterface>, is left out with an error.
std::vector<transmission_interface::TransmissionInfo> ParseTransmissions(const std::string& urdf)
{
  std::vector<transmission_interface::TransmissionInfo> out;
  TiXmlDocument doc;
  if (!doc.Parse(urdf.c_str()) && doc.Error())
  {
    ROS_ERROR("Can't parse transmissions. Invalid robot description.");
    return out;
  }
  for (const TiXmlElement* t = doc.RootElement()->FirstChildElement("transmission"); t;
       t = t->NextSiblingElement("transmission"))
  {
    transmission_interface::TransmissionInfo info;
    const TiXmlElement* type = t->FirstChildElement("type");
    if (!t->Attribute("name") || !type || !type->GetText())
    {
      ROS_ERROR_STREAM("A transmission without a name or a <type> was skipped: " << Text(t));
      continue;
    }
    info.name_ = t->Attribute("name");
    info.type_ = type->GetText();
    bool ok = true;
    for (const TiXmlElement* j = t->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint"))
    {
      transmission_interface::JointInfo joint;
      joint.hardware_interfaces_ = Interfaces(j);
      if (!j->Attribute("name") || joint.hardware_interfaces_.empty())
      {
        ROS_ERROR_STREAM("Transmission '" << info.name_ << "': a joint without a name or a <hardwareInterface>; "
                                             "the transmission is skipped");
        ok = false;
        break;
      }
      joint.name_ = j->Attribute("name");
      const TiXmlElement* role = j->FirstChildElement("role");
      joint.role_ = role && role->GetText() ? role->GetText() : "";
      joint.xml_element_ = Text(j);
      info.joints_.push_back(joint);
    }
    for (const TiXmlElement* a = t->FirstChildElement("actuator"); ok && a; a = a->NextSiblingElement("actuator"))
    {
      transmission_interface::ActuatorInfo actuator;
      actuator.name_ = a->Attribute("name") ? a->Attribute("name") : "";
      actuator.hardware_interfaces_ = Interfaces(a);
      actuator.xml_element_ = Text(a);
      info.actuators_.push_back(actuator);
    }
    if (ok)
      out.push_back(info);
  }
  return out;
}

struct Loaded
{
  std::string name, type, label;
  controller_interface::ControllerBase::ClaimedResources claimed;
  std::vector<size_t> commanded;  // the joints whose commands it claimed, by index
  std::set<std::string> claimed_joints;  // the same by name (a RobotHWSim's joints)
  bool running = false;
  std::shared_ptr<controller_interface::ControllerBase> controller;
};

// The C++ controllers of one controller manager, on one robot's joints.
class Host
{
public:
  // joints: (name, interface, Python JointHandle) for every joint of the robot's RobotHWSim.
  // joints: (name, interface, Python JointHandle) for every joint of the robot's DefaultRobotHWSim; none for a
  // robot whose RobotHWSim is a package's own (InitSim).
  Host(const std::string& ns, const std::vector<std::tuple<std::string, std::string, py::object>>& joints)
    : ns(ns)
  {
    {
      // pluginlib crawls every package's exports (rospack): the simulation and the services go on meanwhile
      py::gil_scoped_release release;
      loader = Shared<Loader>("controller_interface", "controller_interface::ControllerBase");
    }
    std::vector<std::pair<std::string, std::string>> described;
    for (const auto& joint : joints)
    {
      described.emplace_back(std::get<0>(joint), std::get<1>(joint));
      handles.push_back(std::get<2>(joint));
    }
    sim_hw.reset(new SimRobotHW(described));
    hw = sim_hw.get();
    crash::Install();
  }

  ~Host() { Close(); }

  // The controllers, then the RobotHWSim, then the loaders that hold their libraries.
  void Close()
  {
    std::vector<py::object> gone;
    gone.swap(handles);
    for (Mirrored& m : mirror)
      gone.push_back(m.handle);
    mirror.clear();
    py::gil_scoped_release release;
    controllers.clear();
    hw = sim_hw.get();
    robot_hw_sim.reset();
    sim_loader.reset();
  }

  // gazebo_ros_control's Load with <robotSimType> `type`: the URDF from the parameter `robot_param` (searched up
  // from the robot's namespace, else read in it; upstream waits for it, this fails at once), its transmissions, the
  // RobotHWSim made through pluginlib and its initSim. Its joints as [(name, [command interfaces])], every joint of
  // its JointStateInterface; std::runtime_error saying why when it cannot be made or initSim fails.
  std::vector<std::pair<std::string, std::vector<std::string>>> InitSim(const std::string& type,
                                                                       const std::string& robot_namespace,
                                                                       const std::string& robot_param,
                                                                       py::capsule model)
  {
    gazebo::physics::ModelPtr parent = *static_cast<gazebo::physics::ModelPtr*>(model.get_pointer());
    {
      py::gil_scoped_release release;  // initSim calls the engine, which takes the lock per call
      ros::NodeHandle model_nh(robot_namespace);
      // gazebo_ros_control's getURDF: searched up from the namespace, else read under it. NodeHandle("/"), the
      // namespace spawn_model gives every plugin, has the namespace "" and its searchParam finds nothing.
      std::string found, urdf_xml;
      if (!(model_nh.searchParam(robot_param, found) && model_nh.getParam(found, urdf_xml)) &&
          !model_nh.getParam(robot_param, urdf_xml))
        throw std::runtime_error("no URDF on the parameter server under '" + robot_param + "' (searched from '" +
                                 robot_namespace + "'); set <robotParam> or load the robot's description");
      const std::vector<transmission_interface::TransmissionInfo> infos = ParseTransmissions(urdf_xml);
      sim_loader = Shared<SimLoader>("gazebo_ros_control", "gazebo_ros_control::RobotHWSim");
      try
      {
        robot_hw_sim = sim_loader->createSharedInstance(type);
      }
      catch (const pluginlib::PluginlibException& error)
      {
        throw std::runtime_error("pluginlib could not make the RobotHWSim " + type + ": " + error.what());
      }
      const urdf::Model* urdf = urdf_model.initString(urdf_xml) ? &urdf_model : nullptr;
      bool ok = false;
      try
      {
        crash::Running running("RobotHWSim " + type);
        ok = robot_hw_sim->initSim(robot_namespace, model_nh, parent, urdf, infos);
      }
      catch (const std::exception& error)
      {
        throw std::runtime_error("the RobotHWSim " + type + "'s initSim threw: " + error.what());
      }
      if (!ok)
        throw std::runtime_error("the RobotHWSim " + type + "'s initSim returned false (its own error is in the "
                                 "world server's log, from its roscpp node)");
    }
    hw = robot_hw_sim.get();
    sim_label = "RobotHWSim " + type;
    std::vector<std::pair<std::string, std::vector<std::string>>> joints;
    auto* states = hw->get<hardware_interface::JointStateInterface>();
    for (const std::string& name : states ? states->getNames() : std::vector<std::string>())
    {
      std::vector<std::string> interfaces;
      for (const char* interface : kCommandInterfaces)
      {
        auto* commands = CommandInterface(*hw, interface);
        if (commands)
        {
          const std::vector<std::string> names = commands->getNames();
          if (std::find(names.begin(), names.end(), name) != names.end())
            interfaces.push_back(interface);
        }
      }
      joints.emplace_back(name, interfaces);
    }
    return joints;
  }

  // The Python handles of the RobotHWSim's joints: (name, interface it is commanded through or '', handle).
  void BindMirror(const std::vector<std::tuple<std::string, std::string, py::object>>& joints)
  {
    auto* states = hw->get<hardware_interface::JointStateInterface>();
    mirror.clear();
    for (const auto& joint : joints)
    {
      Mirrored m;
      m.state = states->getHandle(std::get<0>(joint));
      if (!std::get<1>(joint).empty())
      {
        m.command = CommandInterface(*hw, std::get<1>(joint))->getHandle(std::get<0>(joint));
        m.commanded = true;
      }
      m.handle = std::get<2>(joint);
      mirror.push_back(m);
    }
  }

  // readSim, then the states into the Python handles.
  void ReadSim(double time, double period)
  {
    {
      py::gil_scoped_release release;
      crash::Running running(sim_label);
      robot_hw_sim->readSim(ros::Time(time), ros::Duration(period));
    }
    static const py::str position("position"), velocity("velocity"), effort("effort");
    for (Mirrored& m : mirror)
    {
      m.handle.attr(position) = m.state.getPosition();
      m.handle.attr(velocity) = m.state.getVelocity();
      m.handle.attr(effort) = m.state.getEffort();
    }
  }

  // The Python controllers' commands (joints no running C++ controller claimed), then writeSim.
  void WriteSim(double time, double period)
  {
    std::set<std::string> cpp;
    for (const auto& entry : controllers)
      if (entry.second->running)
        cpp.insert(entry.second->claimed_joints.begin(), entry.second->claimed_joints.end());
    static const py::str command("command");
    for (Mirrored& m : mirror)
      if (m.commanded && !cpp.count(m.state.getName()))
        m.command.setCommand(m.handle.attr(command).cast<double>());
    py::gil_scoped_release release;
    crash::Running running(sim_label);
    robot_hw_sim->writeSim(ros::Time(time), ros::Duration(period));
  }

  void EStopActive(bool active)
  {
    py::gil_scoped_release release;
    robot_hw_sim->eStopActive(active);
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

  // A RobotHWSim class `type` declared to pluginlib whose library is there.
  bool SimAvailable(const std::string& type)
  {
    py::gil_scoped_release release;
    auto simulated = Shared<SimLoader>("gazebo_ros_control", "gazebo_ros_control::RobotHWSim");
    if (!simulated->isClassAvailable(type))
      return false;
    try
    {
      return !simulated->getClassLibraryPath(type).empty();
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
        ok = made->controller->initRequest(hw, root, own, made->claimed);
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
          made->claimed_joints.insert(resource);
          if (!sim_hw)
            continue;
          auto found = sim_hw->index.find(resource);
          if (found != sim_hw->index.end())
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

  void Starting(int id, double time)
  {
    Call(id, [time](controller_interface::ControllerBase& c) { c.startRequest(ros::Time(time)); });
    Get(id).running = true;
  }
  void Stopping(int id, double time)
  {
    Get(id).running = false;
    Call(id, [time](controller_interface::ControllerBase& c) { c.stopRequest(ros::Time(time)); });
  }
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

  // The joints' state and commands from the Python handles (a DefaultRobotHWSim's; a RobotHWSim's are its own).
  void Read()
  {
    static const py::str position("position"), velocity("velocity"), effort("effort"), command("command");
    for (size_t i = 0; i < handles.size(); ++i)
    {
      const py::handle h = handles[i];
      sim_hw->pos[i] = h.attr(position).cast<double>();
      sim_hw->vel[i] = h.attr(velocity).cast<double>();
      sim_hw->eff[i] = h.attr(effort).cast<double>();
      sim_hw->cmd[i] = h.attr(command).cast<double>();
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
      handles[i].attr(command) = sim_hw->cmd[i];
  }

  std::string ns;
  std::shared_ptr<Loader> loader;
  std::unique_ptr<SimRobotHW> sim_hw;  // over the Python handles of a DefaultRobotHWSim
  std::shared_ptr<SimLoader> sim_loader;
  std::shared_ptr<gazebo_ros_control::RobotHWSim> robot_hw_sim;  // or a package's own
  urdf::Model urdf_model;
  std::string sim_label;
  std::vector<Mirrored> mirror;
  hardware_interface::RobotHW* hw = nullptr;  // the one the controllers get
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
    .def("unload", &Host::Unload, py::arg("id"))
    .def("sim_available", &Host::SimAvailable, py::arg("type"))
    .def("init_sim", &Host::InitSim, py::arg("type"), py::arg("robot_namespace"), py::arg("robot_param"),
         py::arg("model"))
    .def("close", &Host::Close)
    .def("bind_mirror", &Host::BindMirror, py::arg("joints"))
    .def("read_sim", &Host::ReadSim, py::arg("time"), py::arg("period"))
    .def("write_sim", &Host::WriteSim, py::arg("time"), py::arg("period"))
    .def("estop_active", &Host::EStopActive, py::arg("active"));
}

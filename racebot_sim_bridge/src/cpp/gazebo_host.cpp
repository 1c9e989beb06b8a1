// gazebo_host: racebot's host of compiled Gazebo plugins, the one seam where its Python simulator and C++ meet.
//
// A plugin library built against racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev) is loaded here as
// Gazebo loads one (dlopen, RegisterPlugin, GetType, Load with the model and its <plugin> element, Init), and
// racebot's world server fires Gazebo's events through it at each world update. Every physics call a plugin makes
// (gazebo::physics::Joint::SetVelocity, Link::WorldPose, ...) comes back here, to PyEngine, which calls the Python
// adapter (racebot_sim_bridge.gazebo_plugins.compiled_plugins.EngineAdapter), taking the interpreter lock for that
// call only: the world update releases it while plugin code runs, so a plugin's own ROS threads (its callbacks
// on roscpp's spinner, which may call the physics too) never wait on a lock the update holds while it waits on
// theirs. roscpp runs in the world server as gazebo_ros's system plugin starts it (start_roscpp: ros::init with no
// SIGINT handler, an AsyncSpinner on the global queue), under a node name of its own beside the rospy node.
// Built by racebot_sim_bridge/CMakeLists.txt into the devel space's gazebo_plugins folder.
#include <dlfcn.h>
#include <string.h>

#include <chrono>
#include <map>
#include <memory>
#include <unordered_map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <ros/ros.h>

#include <gazebo/common/Events.hh>
#include <gazebo/common/Plugin.hh>
#include <gazebo/physics/physics.hh>
#include <gazebo/racebot/Engine.hh>
#include <gazebo/rendering/Camera.hh>
#include <gazebo/sensors/CameraSensor.hh>
#include <gazebo/sensors/ContactSensor.hh>
#include <gazebo/sensors/GpuRaySensor.hh>
#include <gazebo/sensors/ImuSensor.hh>
#include <gazebo/sensors/RaySensor.hh>
#include <gazebo/transport/Node.hh>
#include <racebot_sim_bridge/fatal_signals.h>

namespace py = pybind11;
using ignition::math::Pose3d;
using ignition::math::Vector3d;

namespace
{
using PoseT = std::tuple<double, double, double, double, double, double, double>;

// A pose from Python, (x, y, z, qx, qy, qz, qw): PyBullet's order
Pose3d PoseOf(const PoseT &_p)
{
  return Pose3d(std::get<0>(_p), std::get<1>(_p), std::get<2>(_p), std::get<6>(_p), std::get<3>(_p), std::get<4>(_p),
                std::get<5>(_p));
}

// The Engine behind gazebo::physics: each call one method of the Python adapter, looked up once.
class PyEngine : public gazebo::racebot::Engine
{
public:
  explicit PyEngine(py::object _adapter) : adapter(std::move(_adapter))
  {
    for (const char *name : {"sim_time", "step_size", "gravity", "joint_position", "joint_velocity",
                             "joint_set_velocity", "joint_set_force", "joint_set_position",
                             "joint_set_motor", "link_world_pose", "link_world_cog_pose", "link_world_linear_vel",
                             "link_world_cog_linear_vel", "link_world_angular_vel", "link_add_force",
                             "link_add_torque", "link_mass", "link_inertial", "link_world_force", "link_world_torque",
                             "joint_wrench", "model_set_world_pose", "model_set_linear_vel", "model_set_angular_vel",
                             "model_world_pose"})
      this->methods[name] = this->adapter.attr(name);
  }

  // During a world update, the time it steps to (Gazebo adds the step to its sim time before World::Update, so
  // World::SimTime() in an event callback is UpdateInfo::simTime); between updates, the simulator's.
  double SimTime() override { return this->inUpdate ? this->updateTime : this->Get<double>("sim_time"); }
  double RealTime() override
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->started).count();
  }
  double StepSize() override { return this->Get<double>("step_size"); }
  Vector3d Gravity() override { return V(this->Get<Vec>("gravity")); }

  double JointPosition(int _j) override { return this->Get<double>("joint_position", _j); }
  double JointVelocity(int _j) override { return this->Get<double>("joint_velocity", _j); }
  // Joint::SetForce adds for the coming step, and the first call of a later update starts again from zero (ODE's
  // Joint::SaveForce); GetForce reads the last sum until then
  double JointForce(int _j) override
  {
    auto found = this->efforts.find(_j);
    return found == this->efforts.end() ? 0.0 : found->second.second;
  }
  void JointSetVelocity(int _j, double _v) override { this->Call("joint_set_velocity", _j, _v); }
  void JointSetForce(int _j, double _f) override
  {
    // keyed by the time of the step the force is for: a RobotHWSim's writeSim sets forces between updates
    const double now = this->SimTime();
    auto &saved = this->efforts[_j];
    if (saved.first != now)
      saved = {now, 0.0};
    saved.second += _f;
    this->Call("joint_set_force", _j, saved.second);
  }
  void JointSetPosition(int _j, double _p) override { this->Call("joint_set_position", _j, _p); }
  void JointSetMotor(int _j, double _v, double _f) override { this->Call("joint_set_motor", _j, _v, _f); }

  Pose3d LinkWorldPose(int _l) override { return PoseOf(this->Get<PoseT>("link_world_pose", _l)); }
  Pose3d LinkWorldCoGPose(int _l) override { return PoseOf(this->Get<PoseT>("link_world_cog_pose", _l)); }
  Vector3d LinkWorldLinearVel(int _l) override { return V(this->Get<Vec>("link_world_linear_vel", _l)); }
  Vector3d LinkWorldCoGLinearVel(int _l) override { return V(this->Get<Vec>("link_world_cog_linear_vel", _l)); }
  Vector3d LinkWorldAngularVel(int _l) override { return V(this->Get<Vec>("link_world_angular_vel", _l)); }
  void LinkAddForce(int _l, const Vector3d &_f) override { this->Call("link_add_force", _l, Vec(_f.X(), _f.Y(), _f.Z())); }
  void LinkAddTorque(int _l, const Vector3d &_t) override
  {
    this->Call("link_add_torque", _l, Vec(_t.X(), _t.Y(), _t.Z()));
  }
  double LinkMass(int _l) override { return this->Get<double>("link_mass", _l); }
  void LinkInertial(int _l, double &_mass, Pose3d &_pose, Vector3d &_principal) override
  {
    auto inertial = this->Get<std::tuple<double, PoseT, Vec>>("link_inertial", _l);
    _mass = std::get<0>(inertial);
    _pose = PoseOf(std::get<1>(inertial));
    _principal = V(std::get<2>(inertial));
  }
  Vector3d LinkWorldForce(int _l) override { return V(this->Get<Vec>("link_world_force", _l)); }
  Vector3d LinkWorldTorque(int _l) override { return V(this->Get<Vec>("link_world_torque", _l)); }
  void JointWrench(int _j, Vector3d &_force, Vector3d &_torque) override
  {
    auto wrench = this->Get<std::tuple<Vec, Vec>>("joint_wrench", _j);
    _force = V(std::get<0>(wrench));
    _torque = V(std::get<1>(wrench));
  }

  void ModelSetWorldPose(int _m, const Pose3d &_p) override
  {
    this->Call("model_set_world_pose", _m, PoseT(_p.Pos().X(), _p.Pos().Y(), _p.Pos().Z(), _p.Rot().X(),
                                                 _p.Rot().Y(), _p.Rot().Z(), _p.Rot().W()));
  }
  void ModelSetLinearVel(int _m, const Vector3d &_v) override
  {
    this->Call("model_set_linear_vel", _m, Vec(_v.X(), _v.Y(), _v.Z()));
  }
  void ModelSetAngularVel(int _m, const Vector3d &_v) override
  {
    this->Call("model_set_angular_vel", _m, Vec(_v.X(), _v.Y(), _v.Z()));
  }
  Pose3d ModelWorldPose(int _m) override { return PoseOf(this->Get<PoseT>("model_world_pose", _m)); }

private:
  // A Python error becomes py::error_already_set, a std::exception: the event reports it against the plugin.
  // The value comes back as a C++ value, converted under the lock (a py::object outliving it would not be).
  template<typename R, typename... Args>
  R Get(const char *_name, Args &&... _args)
  {
    py::gil_scoped_acquire lock;
    return this->methods.at(_name)(std::forward<Args>(_args)...).template cast<R>();
  }

  template<typename... Args>
  void Call(const char *_name, Args &&... _args)
  {
    py::gil_scoped_acquire lock;
    this->methods.at(_name)(std::forward<Args>(_args)...);
  }

  using Vec = std::tuple<double, double, double>;
  static Vector3d V(const Vec &_v) { return Vector3d(std::get<0>(_v), std::get<1>(_v), std::get<2>(_v)); }


  py::object adapter;
  std::map<std::string, py::object> methods;

public:
  // set by the host around each world update
  void BeginUpdate(double _time)
  {
    this->inUpdate = true;
    this->updateTime = _time;
  }
  void EndUpdate() { this->inUpdate = false; }

private:
  bool inUpdate = false;
  double updateTime = 0.0;
  std::unordered_map<int, std::pair<double, double>> efforts;  // joint -> (update time, effort summed then)
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
};

// A crash inside a plugin's code (a bad pointer) ends the world server, as in Gazebo, but its log says which
// plugin was running: the fatal signal's handler names the plugin on whose behalf the crashing thread ran (the
// current owner: its Load, Init, Reset or event callback), or lists the loaded plugins when none was (a plugin's
// own ROS callback), then hands the signal on to the handler before it (Python's faulthandler, or the default).
namespace crash
{
using racebot::fatal_signals::Say;
constexpr int kSlots = 64;
constexpr int kLabel = 200;
char labels[kSlots][kLabel];  // by plugin id % kSlots; written while loading, read by the handler
int ids[kSlots];
racebot::fatal_signals::Chain chain;

void Handler(int _signal, siginfo_t *, void *)
{
  const int owner = gazebo::event::detail::CurrentOwner();
  Say("\nracebot: the world server crashed (");
  Say(racebot::fatal_signals::Name(_signal));
  if (owner > 0 && ids[owner % kSlots] == owner)
  {
    Say(") inside compiled ");
    Say(labels[owner % kSlots]);
    Say(", in its own code: fix or rebuild that plugin, or remove it from the robot's URDF\n");
  }
  else
  {
    Say(") outside any compiled plugin's Load, Init, Reset or event callback; compiled plugins loaded:");
    for (int i = 0; i < kSlots; ++i)
      if (ids[i] > 0)
      {
        Say(" ");
        Say(labels[i]);
        Say(";");
      }
    Say(" (a crash in a plugin's ROS callback shows here too)\n");
  }
  chain.PassOn(_signal);
}

void Install() { chain.Install(Handler); }

void Remember(int _id, const std::string &_label)
{
  ids[_id % kSlots] = _id;
  strncpy(labels[_id % kSlots], _label.c_str(), kLabel - 1);
  labels[_id % kSlots][kLabel - 1] = '\0';
}

void Forget(int _id)
{
  if (ids[_id % kSlots] == _id)
    ids[_id % kSlots] = 0;
}
}  // namespace crash

// One loaded plugin: what it is, for the messages, and the object itself.
struct Loaded
{
  std::string label;
  gazebo::PluginType type;
  boost::shared_ptr<gazebo::ModelPlugin> model;
  boost::shared_ptr<gazebo::WorldPlugin> world;
  boost::shared_ptr<gazebo::SensorPlugin> sensor;
  boost::shared_ptr<gazebo::SystemPlugin> system;
};

// numpy's float64 arrays, as the sensor's measurement comes from racebot's ray casts
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
std::vector<double> ToVector(const Doubles &_array)
{
  return std::vector<double>(_array.data(), _array.data() + _array.size());
}

class Host
{
  using Vec = std::tuple<double, double, double>;
  static Vector3d V(const Vec &_v) { return Vector3d(std::get<0>(_v), std::get<1>(_v), std::get<2>(_v)); }

public:
  // `_notify(kind, value)`: called (rarely) with ('failures', [(id, label, message)]) when plugins' callbacks threw
  // and were unloaded, and with ('wants_end', bool) when worldUpdateEnd gains its first or loses its last callback.
  Host(py::object _adapter, const std::string &_worldName, py::object _notify)
    : engine(new PyEngine(std::move(_adapter))), world(new gazebo::physics::World(_worldName)),
      notify(std::move(_notify))
  {
    // the newest host is the one gazebo::physics calls (a world server has one; a test makes one per world)
    gazebo::racebot::SetEngine(this->engine.get());
    gazebo::physics::set_world(this->world);
    Active() = this;
    this->info.worldName = _worldName;
  }

  ~Host()
  {
    this->Close();
    if (Active() == this)
    {
      gazebo::physics::set_world(gazebo::physics::WorldPtr());
      gazebo::racebot::SetEngine(nullptr);
      Active() = nullptr;
    }
  }

  // links: [(name, handle)], the canonical link first; joints: [(name, handle, parent link, child link, lower,
  // upper, effort limit, velocity limit)]
  void AddModel(const std::string &_name, int _handle, bool _static,
                const std::vector<std::tuple<std::string, int>> &_links,
                const std::vector<std::tuple<std::string, int, std::string, std::string, double, double, double,
                                             double>> &_joints)
  {
    auto model = boost::make_shared<gazebo::physics::Model>(this->world, _name, _handle, _static);
    std::map<std::string, gazebo::physics::LinkPtr> links;
    for (const auto &l : _links)
    {
      auto link = boost::make_shared<gazebo::physics::Link>(model, std::get<0>(l), std::get<1>(l));
      links[std::get<0>(l)] = link;
      model->AddLink(link);
    }
    for (const auto &j : _joints)
    {
      gazebo::physics::JointLimits limits;
      limits.lower = std::get<4>(j);
      limits.upper = std::get<5>(j);
      limits.effort = std::get<6>(j);
      limits.velocity = std::get<7>(j);
      auto parent = links.count(std::get<2>(j)) ? links[std::get<2>(j)] : gazebo::physics::LinkPtr();
      auto child = links.count(std::get<3>(j)) ? links[std::get<3>(j)] : gazebo::physics::LinkPtr();
      model->AddJoint(boost::make_shared<gazebo::physics::Joint>(model, std::get<0>(j), std::get<1>(j), parent,
                                                                 child, limits));
    }
    this->world->AddModel(model);
    this->controlled.push_back(model);
  }

  // The model as gazebo_ros_control hands it to a RobotHWSim's initSim (the controller_host module takes it): a
  // capsule owning a ModelPtr, so that the model lives while the RobotHWSim holds it.
  py::capsule ModelCapsule(const std::string &_name)
  {
    gazebo::physics::ModelPtr model = this->world->ModelByName(_name);
    if (!model)
      throw std::runtime_error("no model '" + _name + "' in racebot's Gazebo plugin API world");
    return py::capsule(new gazebo::physics::ModelPtr(model), "gazebo::physics::ModelPtr", [](PyObject *_capsule) {
      delete static_cast<gazebo::physics::ModelPtr *>(PyCapsule_GetPointer(_capsule, "gazebo::physics::ModelPtr"));
    });
  }

  void RemoveModel(const std::string &_name)
  {
    this->world->RemoveModel(_name);
    this->controlled.clear();
    for (const auto &model : this->world->Models())
      this->controlled.push_back(model);
  }

  // Loads the plugin library at `_path` (the <plugin filename> as written: `_filename`) as a plugin of `_kind`
  // ("model": of model `_model`; "world"), with the <plugin> element `_xml`; returns its id. RuntimeError with
  // the reason when the library cannot be loaded, is not a plugin of that kind, or its Load or Init throws.
  int Load(const std::string &_kind, const std::string &_path, const std::string &_filename,
           const std::string &_name, const std::string &_model, const std::string &_xml)
  {
    return this->LoadPlugin(_kind, _path, _filename, _name, _model, _xml, 0);
  }

  // gzserver's command line, which a system plugin's Load(argc, argv) gets; set once, before the first LoadSystem
  // (gazebo_ros_api_plugin keeps the pointers for its ros::init at worldCreated: they live as long as the host).
  void SetServerArgs(const std::vector<std::string> &_args)
  {
    this->serverArgs = _args;
    this->serverArgv.clear();
    for (auto &arg : this->serverArgs)
      this->serverArgv.push_back(&arg[0]);
    this->serverArgv.push_back(nullptr);
  }

  // Loads a system plugin (gzserver's -s LIBRARY), as gazebo_shared::setup does: its Load(argc, argv) with the
  // command line SetServerArgs gave; its id. Init is InitSystem's, once every system plugin is loaded.
  int LoadSystem(const std::string &_path, const std::string &_filename)
  {
    return this->LoadPlugin("system", _path, _filename, _filename, "", "", 0);
  }

  // A system plugin's Init (gazebo_shared::setup calls them after every Load). RuntimeError with the reason when
  // it throws; the plugin is unloaded then.
  void InitSystem(int _id)
  {
    auto found = this->plugins.find(_id);
    if (found == this->plugins.end() || !found->second.system)
      throw std::runtime_error("no system plugin " + std::to_string(_id) + " in racebot's plugin host");
    const std::string label = found->second.label;
    try
    {
      gazebo::event::detail::OwnerScope scope(_id);
      found->second.system->Init();
    }
    catch (const std::exception &_e)
    {
      this->Unload(_id);
      throw std::runtime_error(label + ": in Init: " + _e.what());
    }
  }

  // Gazebo's worldCreated event (World::Load ends with it once the world's models are loaded): a system plugin
  // starts its world-bound work there (physics::get_world(name), its update connections).
  void WorldCreated()
  {
    {
      py::gil_scoped_release unlocked;
      gazebo::event::Events::worldCreated(this->info.worldName);
    }
    this->AfterEvents();
  }

  // gzserver's Server::SigInt: the stop event, then sigInt (gazebo_ros_api_plugin shuts ROS down on it).
  void SigInt()
  {
    {
      py::gil_scoped_release unlocked;
      gazebo::event::Events::stop();
      gazebo::event::Events::sigInt();
    }
    this->AfterEvents();
  }

  // Loads a sensor plugin of the sensor `_sensor` (an Add*Sensor id), as Load loads a model's: Load(sensor,
  // <plugin> element), Init().
  int LoadSensorPlugin(int _sensor, const std::string &_path, const std::string &_filename, const std::string &_name,
                       const std::string &_xml)
  {
    auto found = this->sensors.find(_sensor);
    if (found == this->sensors.end())
      throw std::runtime_error("no sensor " + std::to_string(_sensor) + " in racebot's plugin host");
    const std::string model = found->second->ParentName().substr(0, found->second->ParentName().find("::"));
    return this->LoadPlugin("sensor", _path, _filename, _name, model, _xml, _sensor);
  }

  // A <sensor type="ray"> or "gpu_ray" of model `_model`'s link `_link` for compiled sensor plugins: its id.
  // `_pose`: in the link (x, y, z, qx, qy, qz, qw); `_geometry`: (samples, resolution, min angle, max angle,
  // vertical samples, vertical resolution, vertical min, vertical max, range min, range max, range resolution).
  int AddRaySensor(const std::string &_type, const std::string &_name, const std::string &_model,
                   const std::string &_link, const PoseT &_pose,
                   double _updateRate, bool _alwaysOn, bool _visualize,
                   const std::tuple<int, double, double, double, int, double, double, double, double, double,
                                    double> &_geometry)
  {
    const auto description = this->Describe(_type, _name, _model, _link, _pose, _updateRate, _alwaysOn, _visualize);
    gazebo::physics::MultiRayShape::Geometry geometry;
    std::tie(geometry.samples, geometry.resolution, geometry.minAngle, geometry.maxAngle, geometry.verticalSamples,
             geometry.verticalResolution, geometry.verticalMinAngle, geometry.verticalMaxAngle, geometry.minRange,
             geometry.maxRange, geometry.resRange) = _geometry;
    std::shared_ptr<gazebo::sensors::racebot::RayScan> sensor;
    if (_type == "gpu_ray")
      sensor = std::make_shared<gazebo::sensors::GpuRaySensor>(description, geometry);
    else if (_type == "ray")
      sensor = std::make_shared<gazebo::sensors::RaySensor>(description, geometry);
    else
      throw std::runtime_error("racebot hosts compiled plugins of ray and gpu_ray sensors, not of type " + _type);
    const int id = ++this->lastSensorId;
    this->sensors[id] = sensor;
    return id;
  }

  // A <sensor type="imu"> of model `_model`'s link `_link` (already added) for compiled sensor plugins: its id.
  int AddImuSensor(const std::string &_name, const std::string &_model, const std::string &_link, const PoseT &_pose,
                   double _updateRate, bool _alwaysOn, bool _visualize)
  {
    const auto description = this->Describe("imu", _name, _model, _link, _pose, _updateRate, _alwaysOn, _visualize);
    std::shared_ptr<gazebo::sensors::Sensor> sensor;
    {
      py::gil_scoped_release unlocked;  // its reference orientation is read from the engine
      sensor = std::make_shared<gazebo::sensors::ImuSensor>(description);
    }
    const int id = ++this->lastSensorId;
    this->sensors[id] = sensor;
    return id;
  }

  // A <sensor type="contact"> of model `_model`'s link `_link` for compiled sensor plugins, watching the
  // collisions `_collisions` (its <contact><collision> names): its id.
  int AddContactSensor(const std::string &_name, const std::string &_model, const std::string &_link,
                       const PoseT &_pose, double _updateRate, bool _alwaysOn, bool _visualize,
                       const std::vector<std::string> &_collisions)
  {
    const auto description =
        this->Describe("contact", _name, _model, _link, _pose, _updateRate, _alwaysOn, _visualize);
    const int id = ++this->lastSensorId;
    this->sensors[id] = std::make_shared<gazebo::sensors::ContactSensor>(description, _collisions);
    return id;
  }

  // A <sensor type="camera"> of model `_model`'s link `_link` for compiled sensor plugins: its id. `_camera`:
  // (width, height, format, horizontal fov, near clip, far clip); `_distortion`: (k1, k2, k3, p1, p2, cx, cy), or
  // empty for none.
  int AddCameraSensor(const std::string &_name, const std::string &_model, const std::string &_link,
                      const PoseT &_pose, double _updateRate, bool _alwaysOn, bool _visualize,
                      const std::tuple<unsigned int, unsigned int, std::string, double, double, double> &_camera,
                      const std::vector<double> &_distortion)
  {
    const auto description =
        this->Describe("camera", _name, _model, _link, _pose, _updateRate, _alwaysOn, _visualize);
    gazebo::rendering::DistortionPtr distortion;
    if (_distortion.size() == 7)
      distortion = std::make_shared<gazebo::rendering::Distortion>(
          _distortion[0], _distortion[1], _distortion[2], _distortion[3], _distortion[4],
          ignition::math::Vector2d(_distortion[5], _distortion[6]));
    auto camera = std::make_shared<gazebo::rendering::Camera>(
        _name, this->world->Name() + "::" + description.parentName + "::" + _name, std::get<0>(_camera),
        std::get<1>(_camera), std::get<2>(_camera), std::get<3>(_camera), std::get<4>(_camera), std::get<5>(_camera),
        distortion);
    const int id = ++this->lastSensorId;
    this->sensors[id] = std::make_shared<gazebo::sensors::CameraSensor>(description, camera);
    return id;
  }

  // A camera's (width, height, format, horizontal fov, render rate) now: a plugin may have changed the fov or rate
  std::tuple<unsigned int, unsigned int, std::string, double> CameraState(int _sensor)
  {
    auto sensor = this->SensorAs<gazebo::sensors::CameraSensor>(_sensor, "a camera");
    auto camera = sensor->Camera();
    return std::make_tuple(camera->ImageWidth(), camera->ImageHeight(), camera->ImageFormat(),
                           camera->HFOV().Radian());
  }

  // One frame of a camera at sim time `_time` (CameraSensor::Measure), `_data` ImageByteSize() bytes in its format.
  void MeasureCamera(int _sensor, double _time, const PoseT &_worldPose, const py::bytes &_data)
  {
    auto sensor = this->SensorAs<gazebo::sensors::CameraSensor>(_sensor, "a camera");
    const std::string bytes = _data;
    const unsigned int size = sensor->Camera()->ImageByteSize();
    if (bytes.size() != size)
      throw std::runtime_error("a frame of " + std::to_string(bytes.size()) + " bytes for a camera of " +
                               std::to_string(size));
    std::vector<unsigned char> frame(bytes.begin(), bytes.end());
    {
      py::gil_scoped_release unlocked;
      sensor->Measure(gazebo::common::Time(_time), PoseOf(_worldPose), std::move(frame));
    }
    this->AfterEvents();
  }

  void RemoveSensor(int _sensor) { this->sensors.erase(_sensor); }

  // Whether the sensor measures now (Sensor::IsActive: SetActive, <always_on>, a subscriber of its scan topic)
  // and its update rate (a plugin may have set it): (active, rate).
  std::tuple<bool, double> SensorState(int _sensor)
  {
    const auto &sensor = this->sensors.at(_sensor);
    return std::make_tuple(sensor->IsActive(), sensor->UpdateRate());
  }

  // One measurement of a ray sensor at sim time `_time` (RayScan::Measure): the plugins' callbacks run without the
  // interpreter lock, as event callbacks do; a callback that throws unloads its plugin (AfterEvents).
  void MeasureRay(int _sensor, double _time, const PoseT &_worldPose, const Doubles &_ranges,
                  const Doubles &_intensities, const Doubles &_rawRanges, const Doubles &_rawRetro)
  {
    auto sensor = this->SensorAs<gazebo::sensors::racebot::RayScan>(_sensor, "a ray");
    std::vector<double> ranges = ToVector(_ranges), intensities = ToVector(_intensities);
    std::vector<double> raw = ToVector(_rawRanges), retro = ToVector(_rawRetro);
    {
      py::gil_scoped_release unlocked;
      sensor->Measure(gazebo::common::Time(_time), PoseOf(_worldPose), std::move(ranges), std::move(intensities),
                      std::move(raw), std::move(retro));
    }
    this->AfterEvents();
  }

  // One measurement of an IMU at sim time `_time` (ImuSensor::Measure): the sensor frame's world pose, the angular
  // velocity and linear acceleration in it without and with the sensor's noise.
  void MeasureImu(int _sensor, double _time, const PoseT &_worldPose, const Vec &_angularVel, const Vec &_linearAcc,
                  const Vec &_noisyAngularVel, const Vec &_noisyLinearAcc)
  {
    auto sensor = this->SensorAs<gazebo::sensors::ImuSensor>(_sensor, "an imu");
    {
      py::gil_scoped_release unlocked;
      sensor->Measure(gazebo::common::Time(_time), PoseOf(_worldPose), V(_angularVel), V(_linearAcc),
                      V(_noisyAngularVel), V(_noisyLinearAcc));
    }
    this->AfterEvents();
  }

  // One update of a contact sensor at sim time `_time` (ContactSensor::Measure): `_contacts`, every contact of the
  // steps since the last update: (collision1, collision2, the step's time, positions, normals, depths, and the force
  // and torque on collision1's link per point, in its frame about its centre of mass).
  using ContactT = std::tuple<std::string, std::string, double, std::vector<Vec>, std::vector<Vec>,
                              std::vector<double>, std::vector<Vec>, std::vector<Vec>>;
  void MeasureContacts(int _sensor, double _time, const std::vector<ContactT> &_contacts)
  {
    auto sensor = this->SensorAs<gazebo::sensors::ContactSensor>(_sensor, "a contact");
    std::vector<gazebo::msgs::Contact> contacts(_contacts.size());
    for (size_t i = 0; i < _contacts.size(); ++i)
    {
      const ContactT &c = _contacts[i];
      gazebo::msgs::Contact &contact = contacts[i];
      contact.set_collision1(std::get<0>(c));
      contact.set_collision2(std::get<1>(c));
      gazebo::msgs::Set(contact.mutable_time(), gazebo::common::Time(std::get<2>(c)));
      contact.set_world(this->world->Name());
      for (const Vec &p : std::get<3>(c))
        gazebo::msgs::Set(contact.add_position(), V(p));
      for (const Vec &n : std::get<4>(c))
        gazebo::msgs::Set(contact.add_normal(), V(n));
      for (double d : std::get<5>(c))
        contact.add_depth(d);
      const auto &forces = std::get<6>(c);
      const auto &torques = std::get<7>(c);
      for (size_t j = 0; j < forces.size(); ++j)
      {
        gazebo::msgs::JointWrench *wrench = contact.add_wrench();
        wrench->set_body_1_name(std::get<0>(c));
        wrench->set_body_2_name(std::get<1>(c));
        gazebo::msgs::Set(wrench->mutable_body_1_wrench()->mutable_force(), V(forces[j]));
        gazebo::msgs::Set(wrench->mutable_body_1_wrench()->mutable_torque(),
                          j < torques.size() ? V(torques[j]) : Vector3d::Zero);
      }
    }
    {
      py::gil_scoped_release unlocked;
      sensor->Measure(gazebo::common::Time(_time), std::move(contacts));
    }
    this->AfterEvents();
  }

private:
  // sensor `_sensor` as the kind `T` ("a camera", ...: `_what`), or a RuntimeError saying it is not one
  template<typename T>
  std::shared_ptr<T> SensorAs(int _sensor, const char *_what) const
  {
    auto sensor = std::dynamic_pointer_cast<T>(this->sensors.at(_sensor));
    if (!sensor)
      throw std::runtime_error("sensor " + std::to_string(_sensor) + " is not " + _what + " sensor");
    return sensor;
  }

  gazebo::sensors::Sensor::Description Describe(const std::string &_type, const std::string &_name,
                                                const std::string &_model, const std::string &_link,
                                                const PoseT &_pose, double _updateRate, bool _alwaysOn,
                                                bool _visualize) const
  {
    gazebo::sensors::Sensor::Description description;
    description.name = _name;
    description.type = _type;
    description.parentName = _model + "::" + _link;
    description.worldName = this->world->Name();
    description.id = static_cast<uint32_t>(this->lastSensorId + 1);
    description.pose = PoseOf(_pose);
    description.updateRate = _updateRate;
    description.alwaysOn = _alwaysOn;
    description.visualize = _visualize;
    return description;
  }

  int LoadPlugin(const std::string &_kind, const std::string &_path, const std::string &_filename,
                 const std::string &_name, const std::string &_model, const std::string &_xml, int _sensor)
  {
    const std::string label = _kind == "system" ? "system plugin " + _filename :
                                                  "plugin '" + _name + "' (" + _filename + ")";
    // RTLD_NOW where Gazebo has RTLD_LAZY: a symbol racebot's API lacks is an error now, naming it, not a crash
    // at the plugin's first call
    void *handle = dlopen(_path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (handle == nullptr)
      throw std::runtime_error(label + ": the library cannot be loaded: " + dlerror());
    void *symbol = dlsym(handle, "RegisterPlugin");
    if (symbol == nullptr)
      throw std::runtime_error(label + ": " + _path + " is not a Gazebo plugin: it has no RegisterPlugin (what "
                               "GZ_REGISTER_MODEL_PLUGIN and its kin define)");
    // a system plugin has no <plugin> element: its Load takes the command line
    sdf::ElementPtr sdf = _kind == "system" ? sdf::ElementPtr() : this->PluginElement(label, _xml);
    const int id = ++this->lastId;
    crash::Install();
    crash::Remember(id, (_kind == "world" ? std::string("world ") : _kind == "system" ? std::string() :
                         _kind == "sensor" ? "sensor '" + this->sensors.at(_sensor)->Name() + "' of model '" + _model +
                                               "': " : "model '" + _model + "': ") + label);
    Loaded loaded;
    loaded.label = label;
    gazebo::event::detail::OwnerScope scope(id);
    try
    {
      // RegisterPlugin returns the kind its macro names; every kind keeps its type at the same place
      auto *plugin = reinterpret_cast<gazebo::ModelPlugin *(*)()>(symbol)();
      if (plugin == nullptr)
        throw std::runtime_error("RegisterPlugin returned no plugin");
      loaded.type = plugin->GetType();
      const gazebo::PluginType wanted = _kind == "world" ? gazebo::WORLD_PLUGIN :
                                        _kind == "sensor" ? gazebo::SENSOR_PLUGIN :
                                        _kind == "system" ? gazebo::SYSTEM_PLUGIN : gazebo::MODEL_PLUGIN;
      if (loaded.type != wanted)
      {
        delete plugin;  // its destructor is virtual: the right one runs whatever kind it is
        throw std::runtime_error("is not a " + _kind + " plugin (its GZ_REGISTER_*_PLUGIN names another kind), as "
                                 "Gazebo says: \"detected an incorrect plugin type\"");
      }
      if (loaded.type == gazebo::SENSOR_PLUGIN)
      {
        loaded.sensor.reset(reinterpret_cast<gazebo::SensorPlugin *>(plugin));
        loaded.sensor->SetNames(_filename, _name);
        loaded.sensor->Load(this->sensors.at(_sensor), sdf);
        loaded.sensor->Init();
      }
      else if (loaded.type == gazebo::MODEL_PLUGIN)
      {
        loaded.model.reset(plugin);
        loaded.model->SetNames(_filename, _name);
        gazebo::physics::ModelPtr model = this->world->ModelByName(_model);
        if (!model)
          throw std::runtime_error("model '" + _model + "' is not in the world");
        loaded.model->Load(model, sdf);
        loaded.model->Init();
      }
      else if (loaded.type == gazebo::SYSTEM_PLUGIN)
      {
        loaded.system.reset(reinterpret_cast<gazebo::SystemPlugin *>(plugin));
        loaded.system->SetNames(_filename, _name);
        loaded.system->Load(static_cast<int>(this->serverArgv.size()) - 1, this->serverArgv.data());
      }
      else
      {
        loaded.world.reset(reinterpret_cast<gazebo::WorldPlugin *>(plugin));
        loaded.world->SetNames(_filename, _name);
        loaded.world->Load(this->world, sdf);
        loaded.world->Init();
      }
    }
    catch (const std::exception &_e)
    {
      gazebo::event::DisconnectOwnerEverywhere(id);
      gazebo::transport::racebot::RemoveOwnerSubscriptions(id);
      crash::Forget(id);
      throw std::runtime_error(label + ": " + _e.what());
    }
    this->plugins[id] = loaded;
    this->controlled.clear();
    for (const auto &model : this->world->Models())
      this->controlled.push_back(model);
    return id;
  }

public:
  // Gazebo's World::Update around the physics step: worldUpdateBegin then beforePhysicsUpdate (before), and
  // worldUpdateEnd (after). The world server's step hooks call these directly, at every world update: no Python
  // in between, and Python is called back only when something changed (notify).
  void UpdateBegin(double _simTime)
  {
    {
      py::gil_scoped_release unlocked;  // plugin code may wait on its own ROS threads, which may call the engine
      this->engine->BeginUpdate(_simTime);
      this->info.simTime = gazebo::common::Time(_simTime);
      this->info.realTime = gazebo::common::Time(this->engine->RealTime());
      this->world->SetIterations(++this->iterations);
      gazebo::event::Events::worldUpdateBegin(this->info);
      for (const auto &model : this->controlled)  // Gazebo's Model::Update: the models' JointControllers
        model->Update();
      gazebo::event::Events::beforePhysicsUpdate(this->info);
    }
    this->AfterEvents();
  }

  void UpdateEnd(double)
  {
    {
      py::gil_scoped_release unlocked;
      gazebo::event::Events::worldUpdateEnd();
      this->engine->EndUpdate();
    }
    this->AfterEvents();
  }

  // Between updates (the world paused, or no callback wants worldUpdateEnd): World::SimTime() asks the simulator.
  void Idle() { this->engine->EndUpdate(); }

  // Whether any callback is connected to worldUpdateEnd (the world server calls UpdateEnd only then).
  bool WantsEnd() const { return gazebo::event::Events::worldUpdateEnd.ConnectionCount() > 0; }

  // The world's update count (World::Iterations): the simulator's, at a load and after a reset.
  void SetIterations(uint64_t _iterations) { this->iterations = _iterations; }

  // reset_world / reset_simulation: each plugin's Reset, then the worldReset event
  void Reset()
  {
    {
      py::gil_scoped_release unlocked;
      this->ResetPlugins();
    }
    this->AfterEvents();
  }

  void ResetPlugins()
  {
    for (const auto &model : this->world->Models())
      model->ResetJointController();
    for (auto &entry : this->plugins)
    {
      gazebo::event::detail::OwnerScope scope(entry.first);
      try
      {
        if (entry.second.model)
          entry.second.model->Reset();
        if (entry.second.world)
          entry.second.world->Reset();
        if (entry.second.sensor)
          entry.second.sensor->Reset();
      }
      catch (const std::exception &_e)
      {
        gazebo::event::detail::ReportFailure(entry.first, std::string("in Reset: ") + _e.what());
      }
    }
    gazebo::event::Events::worldReset();
  }

  void Unload(int _id)
  {
    gazebo::event::DisconnectOwnerEverywhere(_id);
    gazebo::transport::racebot::RemoveOwnerSubscriptions(_id);
    crash::Forget(_id);
    auto found = this->plugins.find(_id);
    if (found == this->plugins.end())
      return;
    gazebo::event::detail::OwnerScope scope(_id);
    Loaded loaded = found->second;
    this->plugins.erase(found);
    try
    {
      loaded.model.reset();  // the plugin's destructor (its connections go with it)
      loaded.world.reset();
      loaded.sensor.reset();
      loaded.system.reset();
    }
    catch (...)
    {
    }
  }

  std::vector<int> Ids() const
  {
    std::vector<int> ids;
    for (const auto &entry : this->plugins)
      ids.push_back(entry.first);
    return ids;
  }

  void Close()
  {
    if (!this->plugins.empty())
      gazebo::event::Events::stop();
    for (int id : this->Ids())
      this->Unload(id);
    gazebo::event::detail::TakeFailures();
  }

private:
  static Host *&Active()
  {
    static Host *active = nullptr;
    return active;
  }

  sdf::ElementPtr PluginElement(const std::string &_label, const std::string &_xml)
  {
    sdf::ElementPtr element(new sdf::Element);
    if (!sdf::initFile("plugin.sdf", element))
      throw std::runtime_error(_label + ": sdformat has no description of <plugin> (is libsdformat installed?)");
    sdf::Errors errors;
    if (!sdf::readString("<sdf version='1.6'>" + _xml + "</sdf>", element, errors))
    {
      std::string text = _label + ": sdformat cannot read its <plugin> element";
      for (const auto &error : errors)
        text += "; " + error.Message();
      throw std::runtime_error(text);
    }
    return element;
  }

  // After events ran: plugins whose callbacks threw are unloaded and reported; a change in whether worldUpdateEnd
  // has callbacks is reported (the world server hooks UpdateEnd in or out).
  void AfterEvents()
  {
    auto failures = gazebo::event::detail::TakeFailures();
    if (!failures.empty())
    {
      py::list reported;
      for (const auto &failure : failures)
      {
        auto found = this->plugins.find(failure.first);
        const std::string label = found == this->plugins.end() ? "a plugin" : found->second.label;
        reported.append(py::make_tuple(failure.first, label, failure.second));
        py::gil_scoped_release unlocked;
        this->Unload(failure.first);
      }
      this->notify("failures", reported);
    }
    const bool wants = this->WantsEnd();
    if (wants != this->wantedEnd)
    {
      this->wantedEnd = wants;
      this->notify("wants_end", wants);
    }
  }

  std::unique_ptr<PyEngine> engine;
  gazebo::physics::WorldPtr world;
  py::object notify;
  gazebo::physics::Model_V controlled;  // the models whose Update (JointController) runs at each world update
  bool wantedEnd = false;
  uint64_t iterations = 0;
  gazebo::common::UpdateInfo info;
  std::map<int, Loaded> plugins;
  int lastId = 0;
  std::map<int, std::shared_ptr<gazebo::sensors::Sensor>> sensors;
  int lastSensorId = 0;
  std::vector<std::string> serverArgs;
  std::vector<char *> serverArgv{nullptr};
};
std::unique_ptr<ros::AsyncSpinner> spinner;
std::unique_ptr<ros::NodeHandle> rosNode;

// roscpp in this process, as gazebo_ros_api_plugin starts it in gzserver: ros::init (no SIGINT handler: the
// world server has its own), the node started, an AsyncSpinner serving the global callback queue. `_name`: the
// node's name, `_remappings` the command line's (name:=value, __ns included). False when it was running already.
bool StartRoscpp(const std::string &_name, const std::map<std::string, std::string> &_remappings)
{
  if (ros::isInitialized())
    return false;
  ros::init(_remappings, _name, ros::init_options::NoSigintHandler);
  rosNode.reset(new ros::NodeHandle());
  spinner.reset(new ros::AsyncSpinner(0));
  spinner->start();
  return true;
}

void StopRoscpp()
{
  if (spinner)
    spinner->stop();
  spinner.reset();
  rosNode.reset();
  if (ros::isStarted())
  {
    ros::shutdown();
    ros::waitForShutdown();
  }
}
}  // namespace

PYBIND11_MODULE(gazebo_host, m)
{
  m.doc() = "racebot's host of compiled Gazebo plugins (racebot_sim_bridge/src/cpp/gazebo_host.cpp)";
  py::class_<Host>(m, "Host")
    .def(py::init<py::object, const std::string &, py::object>(), py::arg("adapter"), py::arg("world_name"),
         py::arg("notify"))
    .def("add_model", &Host::AddModel)
    .def("remove_model", &Host::RemoveModel)
    .def("model_capsule", &Host::ModelCapsule)
    // plugin code runs without the interpreter lock (PyEngine takes it for each call into the engine)
    .def("load", &Host::Load, py::arg("kind"), py::arg("path"), py::arg("filename"), py::arg("name"),
         py::arg("model"), py::arg("xml"), py::call_guard<py::gil_scoped_release>())
    .def("set_server_args", &Host::SetServerArgs, py::arg("args"))
    .def("load_system", &Host::LoadSystem, py::arg("path"), py::arg("filename"),
         py::call_guard<py::gil_scoped_release>())
    .def("init_system", &Host::InitSystem, py::arg("id"), py::call_guard<py::gil_scoped_release>())
    .def("world_created", &Host::WorldCreated)  // these release it themselves, around the events
    .def("sig_int", &Host::SigInt)
    .def("add_ray_sensor", &Host::AddRaySensor, py::arg("type"), py::arg("name"), py::arg("model"),
         py::arg("link"), py::arg("pose"), py::arg("update_rate"), py::arg("always_on"), py::arg("visualize"),
         py::arg("geometry"))
    .def("load_sensor_plugin", &Host::LoadSensorPlugin, py::arg("sensor"), py::arg("path"), py::arg("filename"),
         py::arg("name"), py::arg("xml"), py::call_guard<py::gil_scoped_release>())
    .def("add_imu_sensor", &Host::AddImuSensor, py::arg("name"), py::arg("model"), py::arg("link"), py::arg("pose"),
         py::arg("update_rate"), py::arg("always_on"), py::arg("visualize"))
    .def("add_contact_sensor", &Host::AddContactSensor, py::arg("name"), py::arg("model"), py::arg("link"),
         py::arg("pose"), py::arg("update_rate"), py::arg("always_on"), py::arg("visualize"), py::arg("collisions"))
    .def("add_camera_sensor", &Host::AddCameraSensor, py::arg("name"), py::arg("model"), py::arg("link"),
         py::arg("pose"), py::arg("update_rate"), py::arg("always_on"), py::arg("visualize"), py::arg("camera"),
         py::arg("distortion"))
    .def("camera_state", &Host::CameraState)
    .def("remove_sensor", &Host::RemoveSensor)
    .def("sensor_state", &Host::SensorState)
    .def("measure_ray", &Host::MeasureRay)  // these release it themselves, around the plugins' callbacks
    .def("measure_imu", &Host::MeasureImu)
    .def("measure_contacts", &Host::MeasureContacts)
    .def("measure_camera", &Host::MeasureCamera)
    .def("update_begin", &Host::UpdateBegin)  // these release it themselves, around the events
    .def("update_end", &Host::UpdateEnd)
    .def("idle", &Host::Idle)
    .def("wants_end", &Host::WantsEnd)
    .def("set_iterations", &Host::SetIterations)
    .def("reset", &Host::Reset)
    .def("unload", &Host::Unload, py::call_guard<py::gil_scoped_release>())
    .def("ids", &Host::Ids)
    .def("close", &Host::Close, py::call_guard<py::gil_scoped_release>());
  m.def("start_roscpp", &StartRoscpp, py::arg("name"), py::arg("remappings"),
        py::call_guard<py::gil_scoped_release>());
  m.def("stop_roscpp", &StopRoscpp, py::call_guard<py::gil_scoped_release>());
}

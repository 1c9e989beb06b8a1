// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): the plugin base classes and the registration
// macros. A library is a plugin when it exports `RegisterPlugin` (what GZ_REGISTER_*_PLUGIN writes), which returns a
// new plugin whose GetType() says which kind it is; racebot's host loads it as Gazebo does (dlopen with
// RTLD_LAZY | RTLD_GLOBAL, the file found on GAZEBO_PLUGIN_PATH, else by the dynamic linker's own search).
#ifndef GAZEBO_COMMON_PLUGIN_HH_
#define GAZEBO_COMMON_PLUGIN_HH_

#include "gazebo/common/CommonTypes.hh"
#include <dlfcn.h>
#include <sys/stat.h>

#include <cstdlib>
#include <sstream>
#include <string>

#include <boost/shared_ptr.hpp>
#include <sdf/sdf.hh>

#include "gazebo/gazebo_config.h"
#include "gazebo/common/Console.hh"
#include "gazebo/common/Exception.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/rendering/RenderTypes.hh"
#include "gazebo/sensors/SensorTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
enum PluginType
{
  WORLD_PLUGIN,
  MODEL_PLUGIN,
  SENSOR_PLUGIN,
  SYSTEM_PLUGIN,
  VISUAL_PLUGIN,
  GUI_PLUGIN
};

template<class T>
class PluginT
{
public:
  typedef boost::shared_ptr<T> TPtr;

  PluginT() = default;
  // As upstream, the library stays loaded (dlclose after a plugin's destruction crashes plugins' own statics).
  virtual ~PluginT() = default;

  std::string GetFilename() const { return this->filename; }
  std::string GetHandle() const { return this->handleName; }
  PluginType GetType() const { return this->type; }

  // Loads `_filename` (found on GAZEBO_PLUGIN_PATH, else by dlopen's own search) and creates its plugin; null,
  // with an error, when the library or its RegisterPlugin cannot be loaded.
  static TPtr Create(const std::string &_filename, const std::string &_name)
  {
    TPtr result;
    std::string fullname = _filename;
    const char *paths = std::getenv("GAZEBO_PLUGIN_PATH");
    if (paths != nullptr && _filename.find('/') == std::string::npos)
    {
      std::stringstream stream(paths);
      std::string dir;
      struct stat st;
      while (std::getline(stream, dir, ':'))
      {
        if (!dir.empty() && stat((dir + "/" + _filename).c_str(), &st) == 0)
        {
          fullname = dir + "/" + _filename;
          break;
        }
      }
    }
    void *handle = dlopen(fullname.c_str(), RTLD_LAZY | RTLD_GLOBAL);
    if (handle == nullptr)
    {
      gzerr << "Failed to load plugin " << fullname << ": " << dlerror() << "\n";
      return result;
    }
    union
    {
      T *(*func)();
      void *ptr;
    } registerFunc;
    registerFunc.ptr = dlsym(handle, "RegisterPlugin");
    if (registerFunc.ptr == nullptr)
    {
      gzerr << "Failed to resolve RegisterPlugin: " << dlerror();
      return result;
    }
    result.reset(registerFunc.func());
    result->handleName = _name;
    result->filename = _filename;
    return result;
  }

protected:
  template<typename V>
  void LoadParam(const sdf::ElementPtr &_sdf, const std::string &_name, V &_target, V _defaultValue = V()) const
  {
    auto result = _sdf->Get<V>(_name, _defaultValue);
    if (!result.second)
      gzmsg << this->handleName.c_str() << " Plugin missing <" << _name.c_str() << ">, defaults to "
            << result.first << std::endl;
    else
      gzmsg << this->handleName.c_str() << " Plugin <" << _name.c_str() << "> set to " << result.first << std::endl;
    _target = result.first;
  }

  void LoadParam(sdf::ElementPtr &_sdf, const std::string &_name, std::string &_target,
                 const char *_defaultValue) const
  {
    this->LoadParam<std::string>(_sdf, _name, _target, _defaultValue);
  }

  PluginType type;
  std::string filename;
  std::string handleName;

public:
  // racebot's host: names the plugin as Create does, for one it made itself.
  void SetNames(const std::string &_filename, const std::string &_name)
  {
    this->filename = _filename;
    this->handleName = _name;
  }
};

class WorldPlugin : public PluginT<WorldPlugin>
{
public:
  WorldPlugin() { this->type = WORLD_PLUGIN; }
  virtual ~WorldPlugin() {}
  virtual void Load(physics::WorldPtr _world, sdf::ElementPtr _sdf) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

class ModelPlugin : public PluginT<ModelPlugin>
{
public:
  ModelPlugin() { this->type = MODEL_PLUGIN; }
  virtual ~ModelPlugin() {}
  virtual void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

class SensorPlugin : public PluginT<SensorPlugin>
{
public:
  SensorPlugin() { this->type = SENSOR_PLUGIN; }
  virtual ~SensorPlugin() {}
  virtual void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

class SystemPlugin : public PluginT<SystemPlugin>
{
public:
  SystemPlugin() { this->type = SYSTEM_PLUGIN; }
  virtual ~SystemPlugin() {}
  virtual void Load(int _argc = 0, char **_argv = nullptr) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

class VisualPlugin : public PluginT<VisualPlugin>
{
public:
  VisualPlugin() { this->type = VISUAL_PLUGIN; }
  virtual void Load(rendering::VisualPtr _visual, sdf::ElementPtr _sdf) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};
}  // namespace gazebo

#define GZ_REGISTER_MODEL_PLUGIN(classname) \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::ModelPlugin *RegisterPlugin(); \
  gazebo::ModelPlugin *RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_WORLD_PLUGIN(classname) \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::WorldPlugin *RegisterPlugin(); \
  gazebo::WorldPlugin *RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_SENSOR_PLUGIN(classname) \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::SensorPlugin *RegisterPlugin(); \
  gazebo::SensorPlugin *RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_SYSTEM_PLUGIN(classname) \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::SystemPlugin *RegisterPlugin(); \
  gazebo::SystemPlugin *RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_VISUAL_PLUGIN(classname) \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::VisualPlugin *RegisterPlugin(); \
  gazebo::VisualPlugin *RegisterPlugin() { return new classname(); }

#endif

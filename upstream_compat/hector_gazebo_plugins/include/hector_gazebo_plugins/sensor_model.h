// racebot's hector_gazebo_plugins C++ API (upstream_compat/hector_gazebo_plugins): gazebo::SensorModel_<T>, hector's
// sensor error model, for plugins built against racebot's Gazebo 11 plugin API (hector_quadrotor_gazebo_plugins'
// baro). Written against hector_gazebo_plugins 0.5.4's interface; the same model racebot's Python hector plugins
// apply (racebot_sim_bridge/gazebo_plugins/hector_*.py):
//   reading = value * scaleError + error,  error = offset + drift + N(0, gaussianNoise),
//   drift  <- exp(-dt * driftFrequency) * drift + dt * N(0, sqrt(2 * driftFrequency) * drift sigma),
// the drift drawn from N(0, drift sigma) at reset. Parameters from the plugin's SDF: offset, drift, driftFrequency
// (1/3600 Hz), gaussianNoise, scaleError (1), or <prefix>Offset, ... with a prefix; dynamic_reconfigure's
// SensorModelConfig (cfg/SensorModel.cfg) at level 1 sets them, at another level reads them (a vector's mean).
#ifndef HECTOR_GAZEBO_PLUGINS_SENSOR_MODEL_H
#define HECTOR_GAZEBO_PLUGINS_SENSOR_MODEL_H

#include <cmath>
#include <numeric>
#include <random>
#include <string>

#include <ignition/math/Vector3.hh>
#include <sdf/sdf.hh>

#include <hector_gazebo_plugins/SensorModelConfig.h>

namespace gazebo
{
using hector_gazebo_plugins::SensorModelConfig;

namespace sensor_model_detail
{
inline double Gaussian(double _sigma)
{
  thread_local std::mt19937 generator{std::random_device{}()};
  if (!(_sigma > 0.0))
    return 0.0;
  return std::normal_distribution<double>(0.0, _sigma)(generator);
}

// the components of a model's value type, one by one
inline std::size_t Size(const double &) { return 1; }
inline double &At(double &_v, std::size_t) { return _v; }
inline double At(const double &_v, std::size_t) { return _v; }
inline std::size_t Size(const ignition::math::Vector3d &) { return 3; }
inline double &At(ignition::math::Vector3d &_v, std::size_t _i) { return _i == 0 ? _v.X() : _i == 1 ? _v.Y() : _v.Z(); }
inline double At(const ignition::math::Vector3d &_v, std::size_t _i) { return _v[_i]; }

template <typename T> double Mean(const T &_v)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < Size(_v); ++i)
    sum += At(_v, i);
  return Size(_v) ? sum / Size(_v) : 0.0;
}

template <typename T> void Fill(T &_v, double _value)
{
  for (std::size_t i = 0; i < Size(_v); ++i)
    At(_v, i) = _value;
}
}  // namespace sensor_model_detail

template <typename T>
class SensorModel_
{
public:
  SensorModel_() : offset(), drift(), drift_frequency(), gaussian_noise(), scale_error(), current_drift_(), current_error_()
  {
    sensor_model_detail::Fill(this->drift_frequency, 1.0 / 3600.0);  // a drift time constant of an hour
    sensor_model_detail::Fill(this->scale_error, 1.0);
    this->reset();
  }
  virtual ~SensorModel_() = default;

  virtual void Load(sdf::ElementPtr _sdf, const std::string &prefix = std::string())
  {
    auto name = [&prefix](const std::string &_plain, const std::string &_prefixed) {
      return prefix.empty() ? _plain : prefix + _prefixed;
    };
    this->LoadOne(_sdf, name("offset", "Offset"), this->offset);
    this->LoadOne(_sdf, name("drift", "Drift"), this->drift);
    this->LoadOne(_sdf, name("driftFrequency", "DriftFrequency"), this->drift_frequency);
    this->LoadOne(_sdf, name("gaussianNoise", "GaussianNoise"), this->gaussian_noise);
    this->LoadOne(_sdf, name("scaleError", "ScaleError"), this->scale_error);
    this->reset();
  }

  virtual T operator()(const T &value) const { return this->Scaled(value) + this->current_error_; }
  virtual T operator()(const T &value, double dt) { return this->Scaled(value) + this->update(dt); }

  virtual T update(double dt)
  {
    using namespace sensor_model_detail;
    for (std::size_t i = 0; i < Size(this->current_error_); ++i)
    {
      double &drift_now = At(this->current_drift_, i);
      double frequency = At(this->drift_frequency, i);
      drift_now = std::exp(-dt * frequency) * drift_now + dt * Gaussian(std::sqrt(2.0 * frequency) * At(this->drift, i));
      At(this->current_error_, i) = At(this->offset, i) + drift_now + Gaussian(At(this->gaussian_noise, i));
    }
    return this->current_error_;
  }

  virtual void reset()
  {
    using namespace sensor_model_detail;
    this->current_drift_ = this->drift;
    for (std::size_t i = 0; i < Size(this->current_drift_); ++i)
      At(this->current_drift_, i) = Gaussian(At(this->drift, i));
    this->current_error_ = this->current_drift_;
    Fill(this->current_error_, 0.0);
  }

  virtual void reset(const T &value)
  {
    this->current_drift_ = value;
    this->current_error_ = value;
    sensor_model_detail::Fill(this->current_error_, 0.0);
  }

  virtual const T &getCurrentError() const { return this->current_error_; }
  virtual T getCurrentBias() const { return this->current_drift_ + this->offset; }
  virtual const T &getCurrentDrift() const { return this->current_drift_; }
  virtual const T &getScaleError() const { return this->scale_error; }
  virtual void setCurrentDrift(const T &new_drift) { this->current_drift_ = new_drift; }

  virtual void dynamicReconfigureCallback(SensorModelConfig &config, uint32_t level)
  {
    using namespace sensor_model_detail;
    if (level == 1)
    {
      Fill(this->gaussian_noise, config.gaussian_noise);
      Fill(this->offset, config.offset);
      Fill(this->drift, config.drift);
      Fill(this->drift_frequency, config.drift_frequency);
      Fill(this->scale_error, config.scale_error);
    }
    else
    {
      config.gaussian_noise = Mean(this->gaussian_noise);
      config.offset = Mean(this->offset);
      config.drift = Mean(this->drift);
      config.drift_frequency = Mean(this->drift_frequency);
      config.scale_error = Mean(this->scale_error);
    }
  }

  T offset;
  T drift;
  T drift_frequency;
  T gaussian_noise;
  T scale_error;

private:
  // an element's value as sdformat parses it into T; one that does not parse leaves the default, as upstream
  static void LoadOne(const sdf::ElementPtr &_sdf, const std::string &_name, T &_value)
  {
    if (!_sdf->HasElement(_name))
      return;
    sdf::ElementPtr element = _sdf->GetElement(_name);
    T parsed = _value;
    if (element->GetValue() && element->GetValue()->Get(parsed))
      _value = parsed;
  }

  T Scaled(const T &_value) const
  {
    using namespace sensor_model_detail;
    T scaled = _value;
    for (std::size_t i = 0; i < Size(scaled); ++i)
      At(scaled, i) = At(_value, i) * At(this->scale_error, i);
    return scaled;
  }

  T current_drift_;
  T current_error_;
};

typedef SensorModel_<double> SensorModel;
typedef SensorModel_<ignition::math::Vector3d> SensorModel3;
}  // namespace gazebo

#endif

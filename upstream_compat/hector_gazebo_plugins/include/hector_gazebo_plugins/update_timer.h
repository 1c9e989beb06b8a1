// racebot's hector_gazebo_plugins C++ API (upstream_compat/hector_gazebo_plugins): gazebo::UpdateTimer, the update
// clock hector's plugins share (hector_quadrotor_gazebo_plugins' propulsion and baro plugins include it), written
// for racebot's Gazebo 11 plugin API against hector_gazebo_plugins 0.5.4's interface: <prefix>Rate (Hz, 0 = every
// step), <prefix>Period and <prefix>Offset (seconds, or "sec nsec" as sdf::Time wrote them) from the plugin's SDF;
// an update is due when sim time, less the offset, lies within half a step of a multiple of the period.
#ifndef HECTOR_GAZEBO_PLUGINS_UPDATE_TIMER_H
#define HECTOR_GAZEBO_PLUGINS_UPDATE_TIMER_H

#include <cmath>
#include <functional>
#include <sstream>
#include <string>

#include <boost/function.hpp>
#include <sdf/sdf.hh>

#include <gazebo/common/Event.hh>
#include <gazebo/common/Events.hh>
#include <gazebo/common/Time.hh>
#include <gazebo/physics/PhysicsEngine.hh>
#include <gazebo/physics/World.hh>

namespace gazebo
{
class UpdateTimer
{
public:
  UpdateTimer() = default;
  virtual ~UpdateTimer() = default;

  virtual void Load(physics::WorldPtr _world, sdf::ElementPtr _sdf, const std::string &_prefix = "update")
  {
    this->world_ = _world;
    if (_sdf->HasElement(_prefix + "Rate"))
    {
      double rate = _sdf->GetElement(_prefix + "Rate")->Get<double>();
      this->update_period_ = rate > 0.0 ? common::Time(1.0 / rate) : common::Time();
    }
    if (_sdf->HasElement(_prefix + "Period"))
      this->update_period_ = ReadTime(_sdf->GetElement(_prefix + "Period"));
    if (_sdf->HasElement(_prefix + "Offset"))
      this->update_offset_ = ReadTime(_sdf->GetElement(_prefix + "Offset"));
  }

  // `_subscriber` runs at each due world update (the timer connects to worldUpdateBegin once, at the first call)
  virtual event::ConnectionPtr Connect(const boost::function<void()> &_subscriber, bool connectToWorldUpdateBegin = true)
  {
    if (connectToWorldUpdateBegin && !this->update_connection_)
      this->update_connection_ = event::Events::ConnectWorldUpdateBegin(std::bind(&UpdateTimer::Update, this));
    ++this->connection_count_;
    return this->update_event_.Connect(std::function<void()>(_subscriber));
  }

  // drops the world update connection when no subscriber is left (or at once without `_c`); the subscriber's own
  // connection ends when its ConnectionPtr is dropped, as every Gazebo 11 event connection does
  virtual void Disconnect(event::ConnectionPtr const &_c = event::ConnectionPtr())
  {
    if (this->update_connection_ && (!_c || --this->connection_count_ == 0))
      this->update_connection_.reset();
  }

  common::Time const &getUpdatePeriod() const { return this->update_period_; }
  void setUpdatePeriod(common::Time const &_period) { this->update_period_ = _period; }
  double getUpdateRate() const
  {
    double period = this->update_period_.Double();
    return period > 0.0 ? 1.0 / period : 0.0;
  }
  void setUpdateRate(double _rate) { this->update_period_ = _rate > 0.0 ? common::Time(1.0 / _rate) : common::Time(); }
  common::Time const &getLastUpdate() const { return this->last_update_; }
  common::Time getTimeSinceLastUpdate() const
  {
    if (this->last_update_ == common::Time())
      return common::Time();
    return this->world_->SimTime() - this->last_update_;
  }

  virtual bool checkUpdate() const
  {
    double period = this->update_period_.Double();
    if (period == 0.0)
      return true;
    double step = this->world_->Physics()->GetMaxStepSize();
    double phase = std::fmod((this->world_->SimTime() - this->update_offset_).Double() + step / 2.0, period);
    return phase >= 0.0 && phase < step;
  }

  virtual bool update()
  {
    if (!this->checkUpdate())
      return false;
    this->last_update_ = this->world_->SimTime();
    return true;
  }

  virtual bool update(double &_dt)
  {
    _dt = this->getTimeSinceLastUpdate().Double();
    return this->update();
  }

  virtual void Reset() { this->last_update_ = common::Time(); }

protected:
  virtual bool Update()
  {
    if (!this->checkUpdate())
      return false;
    this->update_event_();
    this->last_update_ = this->world_->SimTime();
    return true;
  }

private:
  static common::Time ReadTime(const sdf::ElementPtr &_element)
  {
    std::istringstream in(_element->Get<std::string>());
    double first = 0.0, second = 0.0;
    in >> first;
    if (in >> second)  // "sec nsec"
      return common::Time(static_cast<int32_t>(first), static_cast<int32_t>(second));
    return common::Time(first);
  }

  physics::WorldPtr world_;
  common::Time update_period_;
  common::Time update_offset_;
  common::Time last_update_;
  event::EventT<void()> update_event_;
  unsigned int connection_count_ = 0;
  event::ConnectionPtr update_connection_;
};
}  // namespace gazebo

#endif

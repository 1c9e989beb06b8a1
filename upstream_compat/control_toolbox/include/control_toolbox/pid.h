// racebot's control_toolbox (upstream_compat/control_toolbox): control_toolbox 1.19's Pid, written for racebot and
// header-only (upstream builds it into libcontrol_toolbox). Same public API and the same arithmetic as Noetic's, which
// racebot_sim_bridge's ros_control/pid.py also follows (tests/unit/upstream_compat/test_control_toolbox_pid.py runs
// both on the same inputs):
//   command = p * error + clamp(i * integral(error)) + d * error_dot
// Without antiwindup the integral term is clamped to [i_min, i_max] while the integral itself keeps growing; with
// antiwindup (and i != 0) the integral is clamped to the bounds divided by i. A dt of zero, or a non-finite error or
// error_dot, gives 0.0. The gains sit in a RealtimeBuffer so that dynamic_reconfigure's thread can change them while
// the control loop reads them. init(nh) starts the same dynamic_reconfigure server (ParametersConfig, generated from
// cfg/Parameters.cfg) and, with publish_state, the same control_msgs/PidState publisher on `state` as upstream's.
#ifndef CONTROL_TOOLBOX__PID_H
#define CONTROL_TOOLBOX__PID_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <string>

#include <boost/shared_ptr.hpp>
#include <boost/thread/mutex.hpp>
#include <boost/thread/recursive_mutex.hpp>

#include <ros/ros.h>

#include <control_msgs/PidState.h>
#include <control_toolbox/ParametersConfig.h>
#include <dynamic_reconfigure/server.h>
#include <realtime_tools/realtime_buffer.h>
#include <realtime_tools/realtime_publisher.h>

class TiXmlElement;

namespace control_toolbox
{

class Pid
{
public:
  // One struct so that the control loop reads every gain of one setGains() together.
  struct Gains
  {
    Gains(double p, double i, double d, double i_max, double i_min)
      : p_gain_(p), i_gain_(i), d_gain_(d), i_max_(i_max), i_min_(i_min), antiwindup_(false)
    {
    }
    Gains(double p, double i, double d, double i_max, double i_min, bool antiwindup)
      : p_gain_(p), i_gain_(i), d_gain_(d), i_max_(i_max), i_min_(i_min), antiwindup_(antiwindup)
    {
    }
    Gains() : p_gain_(0.0), i_gain_(0.0), d_gain_(0.0), i_max_(0.0), i_min_(0.0), antiwindup_(false) {}

    double p_gain_;
    double i_gain_;
    double d_gain_;
    double i_max_;  // the integral term's upper bound
    double i_min_;  // and its lower one
    bool antiwindup_;
  };

  Pid(double p = 0.0, double i = 0.0, double d = 0.0, double i_max = 0.0, double i_min = -0.0, bool antiwindup = false)
  {
    setGains(p, i, d, i_max, i_min, antiwindup);
    reset();
  }

  // Copies the gains only, as upstream: no dynamic_reconfigure server and no state publisher (std::vector<Pid> needs it).
  Pid(const Pid& source)
  {
    gains_buffer_ = source.gains_buffer_;
    reset();
  }

  ~Pid() {}

  Pid& operator=(const Pid& source)
  {
    if (this == &source)
      return *this;
    gains_buffer_ = source.gains_buffer_;
    reset();
    return *this;
  }

  void initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup = false)
  {
    setGains(p, i, d, i_max, i_min, antiwindup);
    reset();
  }

  // The node handle is not used: upstream starts the dynamic_reconfigure server in the "pid" namespace.
  void initPid(double p, double i, double d, double i_max, double i_min, const ros::NodeHandle& /*node*/)
  {
    initPid(p, i, d, i_max, i_min);
    ros::NodeHandle nh(defaultNamespace());
    initDynamicReconfig(nh);
  }
  void initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup,
               const ros::NodeHandle& /*node*/)
  {
    initPid(p, i, d, i_max, i_min, antiwindup);
    ros::NodeHandle nh(defaultNamespace());
    initDynamicReconfig(nh);
  }

  bool initParam(const std::string& prefix, const bool quiet = false)
  {
    ros::NodeHandle nh(prefix);
    return init(nh, quiet);
  }

  // Reads p (required), i, d, i_clamp, i_clamp_min, i_clamp_max, antiwindup and publish_state from `node`'s namespace.
  bool init(const ros::NodeHandle& node, const bool quiet = false)
  {
    ros::NodeHandle nh(node);
    Gains gains;
    if (!nh.getParam("p", gains.p_gain_))
    {
      if (!quiet)
        ROS_ERROR("No p gain specified for pid.  Namespace: %s", nh.getNamespace().c_str());
      return false;
    }
    nh.param("i", gains.i_gain_, 0.0);
    nh.param("d", gains.d_gain_, 0.0);

    // i_clamp sets both bounds; i_clamp_min / i_clamp_max override one each. The signs are forced: min <= 0 <= max.
    double i_clamp;
    nh.param("i_clamp", i_clamp, 0.0);
    gains.i_max_ = std::abs(i_clamp);
    gains.i_min_ = -std::abs(i_clamp);
    if (nh.hasParam("i_clamp_min"))
    {
      nh.param("i_clamp_min", gains.i_min_, gains.i_min_);
      gains.i_min_ = -std::abs(gains.i_min_);
    }
    if (nh.hasParam("i_clamp_max"))
    {
      nh.param("i_clamp_max", gains.i_max_, gains.i_max_);
      gains.i_max_ = std::abs(gains.i_max_);
    }
    nh.param("antiwindup", gains.antiwindup_, false);

    nh.param("publish_state", publish_state_, false);
    if (publish_state_)
    {
      state_publisher_.reset(new realtime_tools::RealtimePublisher<control_msgs::PidState>());
      state_publisher_->init(nh, "state", 1);
    }

    setGains(gains);
    reset();
    initDynamicReconfig(nh);
    return true;
  }

  // The attributes p, i, d, iClamp and antiwindup of a TinyXML element. A template only so that this header needs
  // neither tinyxml.h nor its library: a caller holding a TiXmlElement has both.
  template <class Element = TiXmlElement>
  bool initXml(Element* config)
  {
    ros::NodeHandle nh(defaultNamespace());
    const double i_clamp = config->Attribute("iClamp") ? std::atof(config->Attribute("iClamp")) : 0.0;
    setGains(config->Attribute("p") ? std::atof(config->Attribute("p")) : 0.0,
             config->Attribute("i") ? std::atof(config->Attribute("i")) : 0.0,
             config->Attribute("d") ? std::atof(config->Attribute("d")) : 0.0, std::abs(i_clamp), -std::abs(i_clamp),
             config->Attribute("antiwindup") ? std::atof(config->Attribute("antiwindup")) != 0.0 : false);
    reset();
    initDynamicReconfig(nh);
    return true;
  }

  // A dynamic_reconfigure server in `node`'s namespace showing the gains and setting them.
  void initDynamicReconfig(ros::NodeHandle& node)
  {
    ROS_DEBUG_STREAM_NAMED("pid", "Initializing dynamic reconfigure in namespace " << node.getNamespace());
    param_reconfig_server_.reset(new DynamicReconfigServer(param_reconfig_mutex_, node));
    dynamic_reconfig_initialized_ = true;
    updateDynamicReconfig();
    param_reconfig_callback_ =
        std::bind(&Pid::dynamicReconfigCallback, this, std::placeholders::_1, std::placeholders::_2);
    param_reconfig_server_->setCallback(param_reconfig_callback_);
  }

  // Clears the errors, the integral and the command. The next computeCommand(error, dt) differentiates against a
  // previous error of 0, as upstream's does.
  void reset()
  {
    reset(0.0, 0.0);
    valid_p_error_last_ = true;
  }

  // Starts from the given derivative and integral of the error; the next computeCommand(error, dt) uses d_error as
  // its error_dot, having no previous error to differentiate against.
  void reset(double d_error, double i_error)
  {
    p_error_last_ = 0.0;
    p_error_ = 0.0;
    i_error_ = i_error;
    d_error_ = d_error;
    cmd_ = 0.0;
    valid_p_error_last_ = false;
  }

  void getGains(double& p, double& i, double& d, double& i_max, double& i_min)
  {
    bool antiwindup;
    getGains(p, i, d, i_max, i_min, antiwindup);
  }
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup)
  {
    const Gains gains = *gains_buffer_.readFromRT();
    p = gains.p_gain_;
    i = gains.i_gain_;
    d = gains.d_gain_;
    i_max = gains.i_max_;
    i_min = gains.i_min_;
    antiwindup = gains.antiwindup_;
  }
  Gains getGains() { return *gains_buffer_.readFromRT(); }

  void setGains(double p, double i, double d, double i_max, double i_min, bool antiwindup = false)
  {
    setGains(Gains(p, i, d, i_max, i_min, antiwindup));
  }
  void setGains(const Gains& gains)
  {
    gains_buffer_.writeFromNonRT(gains);
    updateDynamicReconfig(gains);
  }

  // Shows the gains in the dynamic_reconfigure server (nothing before initDynamicReconfig).
  void updateDynamicReconfig()
  {
    if (!dynamic_reconfig_initialized_)
      return;
    control_toolbox::ParametersConfig config;
    getGains(config.p, config.i, config.d, config.i_clamp_max, config.i_clamp_min, config.antiwindup);
    updateDynamicReconfig(config);
  }
  void updateDynamicReconfig(Gains gains_config)
  {
    if (!dynamic_reconfig_initialized_)
      return;
    control_toolbox::ParametersConfig config;
    config.p = gains_config.p_gain_;
    config.i = gains_config.i_gain_;
    config.d = gains_config.d_gain_;
    config.i_clamp_max = gains_config.i_max_;
    config.i_clamp_min = gains_config.i_min_;
    config.antiwindup = gains_config.antiwindup_;
    updateDynamicReconfig(config);
  }
  void updateDynamicReconfig(control_toolbox::ParametersConfig config)
  {
    if (!dynamic_reconfig_initialized_)
      return;
    // the server's own mutex: its callback may be running on another thread
    param_reconfig_mutex_.lock();
    param_reconfig_server_->updateConfig(config);
    param_reconfig_mutex_.unlock();
  }

  void dynamicReconfigCallback(control_toolbox::ParametersConfig& config, uint32_t /*level*/)
  {
    ROS_DEBUG_STREAM_NAMED("pid", "Dynamics reconfigure callback recieved.");
    setGains(config.p, config.i, config.d, config.i_clamp_max, config.i_clamp_min, config.antiwindup);
  }

  // error = target - state. error_dot is the change of error over dt; for a negative dt the previous error_dot is
  // used again (and the integral still takes dt * error), as upstream.
  double computeCommand(double error, ros::Duration dt)
  {
    if (dt == ros::Duration(0.0) || std::isnan(error) || std::isinf(error))
      return 0.0;

    double error_dot = d_error_;
    if (dt.toSec() > 0.0)
    {
      if (valid_p_error_last_)
        error_dot = (error - p_error_last_) / dt.toSec();
      p_error_last_ = error;
      valid_p_error_last_ = true;
    }
    return computeCommand(error, error_dot, dt);
  }

  // With the caller's error_dot (e.g. a velocity error); leaves the previous error alone.
  double computeCommand(double error, double error_dot, ros::Duration dt)
  {
    const Gains gains = *gains_buffer_.readFromRT();

    // stored before the check, as upstream does: getCurrentPIDErrors shows the rejected values
    p_error_ = error;
    d_error_ = error_dot;
    if (dt == ros::Duration(0.0) || std::isnan(error) || std::isinf(error) || std::isnan(error_dot) ||
        std::isinf(error_dot))
      return 0.0;

    const double p_term = gains.p_gain_ * p_error_;

    i_error_ += dt.toSec() * p_error_;
    if (gains.antiwindup_ && gains.i_gain_ != 0)
    {
      const double a = gains.i_min_ / gains.i_gain_;
      const double b = gains.i_max_ / gains.i_gain_;
      i_error_ = clamp(i_error_, std::min(a, b), std::max(a, b));
    }
    double i_term = gains.i_gain_ * i_error_;
    if (!gains.antiwindup_)
      i_term = clamp(i_term, gains.i_min_, gains.i_max_);

    const double d_term = gains.d_gain_ * d_error_;
    cmd_ = p_term + i_term + d_term;

    if (publish_state_ && state_publisher_ && state_publisher_->trylock())
    {
      control_msgs::PidState& msg = state_publisher_->msg_;
      msg.header.stamp = ros::Time::now();
      msg.timestep = dt;
      msg.error = error;
      msg.error_dot = error_dot;
      msg.p_error = p_error_;
      msg.i_error = i_error_;
      msg.d_error = d_error_;
      msg.p_term = p_term;
      msg.i_term = i_term;
      msg.d_term = d_term;
      msg.i_max = gains.i_max_;
      msg.i_min = gains.i_min_;
      msg.output = cmd_;
      state_publisher_->unlockAndPublish();
    }
    return cmd_;
  }

  // Pre-Hydro forms: error = state - target, so the command is negated.
  ROS_DEPRECATED double updatePid(double p_error, ros::Duration dt) { return -computeCommand(p_error, dt); }
  ROS_DEPRECATED double updatePid(double error, double error_dot, ros::Duration dt)
  {
    return -computeCommand(error, error_dot, dt);
  }

  void setCurrentCmd(double cmd) { cmd_ = cmd; }
  double getCurrentCmd() { return cmd_; }

  // The last error, the integral of the error (not times i) and the last error_dot.
  void getCurrentPIDErrors(double* pe, double* ie, double* de)
  {
    *pe = p_error_;
    *ie = i_error_;
    *de = d_error_;
  }

  void printValues()
  {
    const Gains gains = getGains();
    ROS_INFO_STREAM_NAMED("pid", "Current Values of PID Class:\n"
                                     << "  P Gain: " << gains.p_gain_ << "\n"
                                     << "  I Gain: " << gains.i_gain_ << "\n"
                                     << "  D Gain: " << gains.d_gain_ << "\n"
                                     << "  I_Max:  " << gains.i_max_ << "\n"
                                     << "  I_Min:  " << gains.i_min_ << "\n"
                                     << "  Antiwindup:  " << gains.antiwindup_ << "\n"
                                     << "  P_Error_Last: " << p_error_last_ << "\n"
                                     << "  P_Error:      " << p_error_ << "\n"
                                     << "  I_Error:       " << i_error_ << "\n"
                                     << "  D_Error:      " << d_error_ << "\n"
                                     << "  Command:      " << cmd_);
  }

private:
  typedef dynamic_reconfigure::Server<control_toolbox::ParametersConfig> DynamicReconfigServer;

  static const char* defaultNamespace() { return "pid"; }
  // boost::algorithm::clamp's order of tests, as upstream's: a NaN stays NaN
  static double clamp(double value, double low, double high)
  {
    return value < low ? low : (high < value ? high : value);
  }

  realtime_tools::RealtimeBuffer<Gains> gains_buffer_;

  boost::shared_ptr<realtime_tools::RealtimePublisher<control_msgs::PidState> > state_publisher_;
  bool publish_state_ = false;

  bool valid_p_error_last_ = false;  // whether p_error_last_ is an error to differentiate against
  double p_error_last_ = 0.0;
  double p_error_ = 0.0;
  double i_error_ = 0.0;  // the integral of the error
  double d_error_ = 0.0;
  double cmd_ = 0.0;

  // The mutex before the server: the server, which locks it, goes first.
  boost::recursive_mutex param_reconfig_mutex_;
  bool dynamic_reconfig_initialized_ = false;
  boost::shared_ptr<DynamicReconfigServer> param_reconfig_server_;
  DynamicReconfigServer::CallbackType param_reconfig_callback_;
};

}  // namespace control_toolbox

#endif  // CONTROL_TOOLBOX__PID_H

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): common::PID, Gazebo's own (gazebo/common/PID.cc):
// command = -(p * error + i-term + d * d(error)/dt), the i-term held within [iMin, iMax], the command clamped to
// [cmdMin, cmdMax] only when cmdMax >= cmdMin (the default cmdMax -1 < cmdMin 0: no clamp). error = state - target.
#ifndef GAZEBO_COMMON_PID_HH_
#define GAZEBO_COMMON_PID_HH_

#include "gazebo/common/Time.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace common
{
class GZ_COMMON_VISIBLE PID
{
public:
  PID(double _p = 0.0, double _i = 0.0, double _d = 0.0, double _imax = 0.0, double _imin = 0.0,
      double _cmdMax = -1.0, double _cmdMin = 0.0);
  virtual ~PID() = default;
  void Init(double _p = 0.0, double _i = 0.0, double _d = 0.0, double _imax = 0.0, double _imin = 0.0,
            double _cmdMax = -1.0, double _cmdMin = 0.0);
  void SetPGain(double _p) { this->pGain = _p; }
  void SetIGain(double _i) { this->iGain = _i; }
  void SetDGain(double _d) { this->dGain = _d; }
  void SetIMax(double _i) { this->iMax = _i; }
  void SetIMin(double _i) { this->iMin = _i; }
  void SetCmdMax(double _c) { this->cmdMax = _c; }
  void SetCmdMin(double _c) { this->cmdMin = _c; }
  double GetPGain() const { return this->pGain; }
  double GetIGain() const { return this->iGain; }
  double GetDGain() const { return this->dGain; }
  double GetIMax() const { return this->iMax; }
  double GetIMin() const { return this->iMin; }
  double GetCmdMax() const { return this->cmdMax; }
  double GetCmdMin() const { return this->cmdMin; }
  double Update(double _error, common::Time _dt);
  void SetCmd(double _cmd) { this->cmd = _cmd; }
  double GetCmd() { return this->cmd; }
  void GetErrors(double &_pe, double &_ie, double &_de)
  {
    _pe = this->pErr;
    _ie = this->iErr;
    _de = this->dErr;
  }
  void Reset();

private:
  double pErrLast = 0.0;
  double pErr = 0.0;
  double iErr = 0.0;
  double dErr = 0.0;
  double pGain, iGain, dGain, iMax, iMin, cmd = 0.0, cmdMax, cmdMin;
};
}  // namespace common
}  // namespace gazebo

#endif

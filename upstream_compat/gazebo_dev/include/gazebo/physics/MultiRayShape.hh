// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): physics::MultiRayShape, a ray sensor's raw rays as
// RaySensor::LaserShape() gives them: one ray per <samples> (horizontal index fastest, the lowest layer first),
// GetRange(i) from range min along the ray (a miss: range max; a ray starting inside an object: range min), no
// noise; GetRetro(i) the laser_retro of what it hit. newLaserScans fires after each cast (RayPlugin's
// OnNewLaserScans), before the sensor's scan message is made. The rays are cast by racebot's simulator
// (sensors/ray_shape.py), not by ODE: Ray(i) and the per-ray shapes are not provided.
#ifndef GAZEBO_PHYSICS_MULTIRAYSHAPE_HH_
#define GAZEBO_PHYSICS_MULTIRAYSHAPE_HH_

#include <mutex>
#include <vector>

#include <ignition/math/Angle.hh>

#include "gazebo/common/Event.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace physics
{
class GZ_PHYSICS_VISIBLE MultiRayShape
{
public:
  // racebot's: the <ray><scan> and <range> a sensor declares
  struct Geometry
  {
    int samples = 1, verticalSamples = 1;
    double resolution = 1.0, verticalResolution = 1.0;
    double minAngle = 0.0, maxAngle = 0.0, verticalMinAngle = 0.0, verticalMaxAngle = 0.0;
    double minRange = 0.0, maxRange = 0.0, resRange = 0.0;
  };

  explicit MultiRayShape(const Geometry &_geometry) : geometry(_geometry) {}
  virtual ~MultiRayShape() = default;

  double GetRange(unsigned int _index);
  double GetRetro(unsigned int _index);
  int GetFiducial(unsigned int _index);  // -1: racebot simulates no fiducials (laser_fiducial)
  double GetMinRange() const { return this->geometry.minRange; }
  double GetMaxRange() const { return this->geometry.maxRange; }
  double GetResRange() const { return this->geometry.resRange; }
  int GetSampleCount() const { return this->geometry.samples; }
  double GetScanResolution() const { return this->geometry.resolution; }
  int GetVerticalSampleCount() const { return this->geometry.verticalSamples; }
  double GetVerticalScanResolution() const { return this->geometry.verticalResolution; }
  ignition::math::Angle MinAngle() const { return this->geometry.minAngle; }
  ignition::math::Angle MaxAngle() const { return this->geometry.maxAngle; }
  ignition::math::Angle VerticalMinAngle() const { return this->geometry.verticalMinAngle; }
  ignition::math::Angle VerticalMaxAngle() const { return this->geometry.verticalMaxAngle; }
  unsigned int RayCount() const;

  template<typename T>
  event::ConnectionPtr ConnectNewLaserScans(T _subscriber)
  {
    return this->newLaserScans.Connect(_subscriber);
  }

  // racebot's host: one cast's raw ranges and retro values (RayCount() of each), then newLaserScans
  void SetRays(std::vector<double> _ranges, std::vector<double> _retro);
  void FireNewLaserScans() { this->newLaserScans(); }

private:
  Geometry geometry;
  std::mutex mutex;
  std::vector<double> ranges;
  std::vector<double> retro;
  event::EventT<void()> newLaserScans;
};
}  // namespace physics
}  // namespace gazebo

#endif

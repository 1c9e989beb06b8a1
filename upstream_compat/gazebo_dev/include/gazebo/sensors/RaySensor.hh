// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): sensors::RaySensor and sensors::GpuRaySensor (a
// <sensor type="ray"> and "gpu_ray"), as gazebo/sensors/RaySensor.hh and GpuRaySensor.hh have them. Both read one
// measurement of racebot's rays: the scan (RangeCount() x VerticalRangeCount() ranges, horizontal index fastest, as
// Gazebo 11's RaySensor reports them: +inf at or beyond range max, -inf at or below range min, else the <noise>
// added and clamped to [min, max]; intensities the laser_retro of what each ray hit), published as a
// msgs::LaserScanStamped on Topic() ("~/<model>/<link>/<sensor>/scan") to transport subscribers. Their shared part
// is racebot's RayScan (not a Gazebo class: RaySensor and GpuRaySensor are unrelated there, so a
// dynamic_pointer_cast to the other one is null here too).
#ifndef GAZEBO_SENSORS_RAYSENSOR_HH_
#define GAZEBO_SENSORS_RAYSENSOR_HH_

#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <ignition/math/Angle.hh>

#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/MultiRayShape.hh"
#include "gazebo/sensors/Sensor.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace sensors
{
namespace racebot
{
class GZ_SENSORS_VISIBLE RayScan : public Sensor
{
public:
  RayScan(const Description &_description, const physics::MultiRayShape::Geometry &_geometry);

  // "~/<parent, :: as />/<name>/scan", as Gazebo's RaySensor::Topic
  std::string Topic() const override;
  // active, or somebody subscribes to Topic() (Gazebo's RaySensor::IsActive)
  bool IsActive() const override;
  ignition::math::Angle AngleMin() const { return this->geometry.minAngle; }
  ignition::math::Angle AngleMax() const { return this->geometry.maxAngle; }
  double AngleResolution() const;
  double RangeMin() const { return this->geometry.minRange; }
  double RangeMax() const { return this->geometry.maxRange; }
  double RangeResolution() const { return this->geometry.resRange; }
  int RayCount() const { return this->geometry.samples; }
  int RangeCount() const;
  int VerticalRayCount() const { return this->geometry.verticalSamples; }
  int VerticalRangeCount() const;
  ignition::math::Angle VerticalAngleMin() const { return this->geometry.verticalMinAngle; }
  ignition::math::Angle VerticalAngleMax() const { return this->geometry.verticalMaxAngle; }
  double VerticalAngleResolution() const;
  void Ranges(std::vector<double> &_ranges) const;
  double Range(const int _index) const;

  // racebot's host: one measurement at sim time `_time` with the sensor at `_worldPose`: the scan's ranges and
  // intensities, and the raw rays' ranges and retro values (MultiRayShape). Fires what Gazebo's RaySensor::Update
  // fires, in its order: the laser shape's newLaserScans, the scan message to its subscribers, the updated event.
  void Measure(const common::Time &_time, const ignition::math::Pose3d &_worldPose, std::vector<double> _ranges,
               std::vector<double> _intensities, std::vector<double> _rawRanges, std::vector<double> _rawRetro);

protected:
  virtual void Cast(std::vector<double> _rawRanges, std::vector<double> _rawRetro) = 0;

  physics::MultiRayShape::Geometry geometry;
  msgs::LaserScanStamped laserMsg;
  const std::string scanTopic;  // Topic(), decoded as transport decodes it (/gazebo/<world>/...)
};
}  // namespace racebot

class GZ_SENSORS_VISIBLE RaySensor : public racebot::RayScan
{
public:
  RaySensor(const Description &_description, const physics::MultiRayShape::Geometry &_geometry);
  double Retro(const int _index) const;
  int Fiducial(const unsigned int _index) const;
  physics::MultiRayShapePtr LaserShape() const { return this->laserShape; }

protected:
  void Cast(std::vector<double> _rawRanges, std::vector<double> _rawRetro) override;

private:
  physics::MultiRayShapePtr laserShape;
};
}  // namespace sensors
}  // namespace gazebo

#endif

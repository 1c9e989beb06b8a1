// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): sensors::GpuRaySensor, a <sensor type="gpu_ray">.
// racebot has no GPU laser: its rays are cast as a ray sensor's (RaySensor.hh says what it reports). The laser
// frame (ConnectNewLaserFrame) is the rays as Gazebo's GpuLaser hands them on: 3 floats a ray (range, retro, 0),
// RayCount() wide and VerticalRayCount() high, format "BLAH" as upstream's. Retro() is 0 and Fiducial() -1, as
// upstream's.
#ifndef GAZEBO_SENSORS_GPURAYSENSOR_HH_
#define GAZEBO_SENSORS_GPURAYSENSOR_HH_

#include <functional>
#include <string>
#include <vector>

#include "gazebo/sensors/RaySensor.hh"

namespace gazebo
{
namespace sensors
{
class GZ_SENSORS_VISIBLE GpuRaySensor : public racebot::RayScan
{
public:
  typedef std::function<void(const float *, unsigned int, unsigned int, unsigned int, const std::string &)>
    LaserFrameCallback;

  GpuRaySensor(const Description &_description, const physics::MultiRayShape::Geometry &_geometry);
  double Retro(const int /*_index*/) const { return 0.0; }
  int Fiducial(const unsigned int /*_index*/) const { return -1; }
  bool IsHorizontal() const { return this->VerticalRayCount() <= 1; }
  unsigned int CameraCount() const { return 1; }
  double HorzFOV() const { return (this->AngleMax() - this->AngleMin()).Radian(); }
  double VertFOV() const { return (this->VerticalAngleMax() - this->VerticalAngleMin()).Radian(); }
  event::ConnectionPtr ConnectNewLaserFrame(LaserFrameCallback _subscriber);

protected:
  void Cast(std::vector<double> _rawRanges, std::vector<double> _rawRetro) override;

private:
  event::EventT<void(const float *, unsigned int, unsigned int, unsigned int, const std::string &)> newLaserFrame;
  std::vector<float> frame;
};
}  // namespace sensors
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): rendering::Distortion, a camera's <distortion> (Brown's
// model: k1, k2, k3, p1, p2, center) as Camera::LensDistortion() returns it. The coefficients are read; racebot's
// images are rendered without the distortion (docs/SUPPORTED.md).
#ifndef GAZEBO_RENDERING_DISTORTION_HH_
#define GAZEBO_RENDERING_DISTORTION_HH_

#include <ignition/math/Vector2.hh>

#include "gazebo/util/system.hh"

namespace gazebo
{
namespace rendering
{
class GZ_RENDERING_VISIBLE Distortion
{
public:
  Distortion(double _k1, double _k2, double _k3, double _p1, double _p2, const ignition::math::Vector2d &_center)
    : k1(_k1), k2(_k2), k3(_k3), p1(_p1), p2(_p2), center(_center) {}
  virtual ~Distortion() = default;
  double K1() const { return this->k1; }
  double K2() const { return this->k2; }
  double K3() const { return this->k3; }
  double P1() const { return this->p1; }
  double P2() const { return this->p2; }
  ignition::math::Vector2d Center() const { return this->center; }
  void SetCrop(const bool _crop) { this->crop = _crop; }
  bool Crop() const { return this->crop; }

private:
  double k1, k2, k3, p1, p2;
  ignition::math::Vector2d center;
  bool crop = false;
};
}  // namespace rendering
}  // namespace gazebo

#endif

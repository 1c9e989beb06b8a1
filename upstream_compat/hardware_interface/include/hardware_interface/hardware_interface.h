// racebot's hardware_interface (upstream_compat/hardware_interface): ros_control 0.20's API, written for racebot.
// The base of every hardware interface: the resources a controller claims while it initializes.
#ifndef HARDWARE_INTERFACE_HARDWARE_INTERFACE_H
#define HARDWARE_INTERFACE_HARDWARE_INTERFACE_H

#include <exception>
#include <set>
#include <string>

namespace hardware_interface
{

class HardwareInterface
{
public:
  virtual ~HardwareInterface() = default;

  virtual void claim(std::string resource) { claims_.insert(std::move(resource)); }
  void clearClaims() { claims_.clear(); }
  std::set<std::string> getClaims() const { return claims_; }

private:
  std::set<std::string> claims_;
};

class HardwareInterfaceException : public std::exception
{
public:
  HardwareInterfaceException(const std::string& message) : message_(message) {}
  const char* what() const noexcept override { return message_.c_str(); }

private:
  std::string message_;
};

}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_HARDWARE_INTERFACE_H

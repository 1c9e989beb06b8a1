// racebot's joint_limits_interface (upstream_compat/joint_limits_interface): ros_control 0.20's API, written for
// racebot. What the limits handles and interfaces throw.
#ifndef JOINT_LIMITS_INTERFACE_JOINT_LIMITS_INTERFACE_EXCEPTION_H
#define JOINT_LIMITS_INTERFACE_JOINT_LIMITS_INTERFACE_EXCEPTION_H

#include <exception>
#include <string>

namespace joint_limits_interface
{

class JointLimitsInterfaceException : public std::exception
{
public:
  JointLimitsInterfaceException(const std::string& message) : message_(message) {}
  const char* what() const noexcept override { return message_.c_str(); }

private:
  std::string message_;
};

}  // namespace joint_limits_interface

#endif  // JOINT_LIMITS_INTERFACE_JOINT_LIMITS_INTERFACE_EXCEPTION_H

// racebot's hardware_interface (upstream_compat/hardware_interface): the C++ API of ros_control 0.20's
// hardware_interface, written for racebot. Type names as the compiler demangles them: the keys interfaces are
// registered and found under (RobotHW::get<T>) and the names list_controllers reports.
#ifndef HARDWARE_INTERFACE_INTERNAL_DEMANGLE_SYMBOL_H
#define HARDWARE_INTERFACE_INTERNAL_DEMANGLE_SYMBOL_H

#include <cxxabi.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <typeinfo>

namespace hardware_interface
{
namespace internal
{

inline std::string demangleSymbol(const char* name)
{
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> demangled(abi::__cxa_demangle(name, nullptr, nullptr, &status), std::free);
  return demangled ? std::string(demangled.get()) : std::string(name);
}

template <class T>
inline std::string demangledTypeName()
{
  return demangleSymbol(typeid(T).name());
}

template <class T>
inline std::string demangledTypeName(const T& value)
{
  return demangleSymbol(typeid(value).name());
}

}  // namespace internal
}  // namespace hardware_interface

#endif  // HARDWARE_INTERFACE_INTERNAL_DEMANGLE_SYMBOL_H

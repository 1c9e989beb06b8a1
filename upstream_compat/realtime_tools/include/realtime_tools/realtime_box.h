// racebot's realtime_tools (upstream_compat/realtime_tools): realtime_tools 1.16's header-only API, written for
// racebot. A value behind a lock (keep a std::shared_ptr in it so that set and get only copy a pointer).
#ifndef REALTIME_TOOLS_REALTIME_BOX_H
#define REALTIME_TOOLS_REALTIME_BOX_H

#include <mutex>

namespace realtime_tools
{

template <class T>
class RealtimeBox
{
public:
  RealtimeBox(const T& initial = T()) : thing_(initial) {}

  void set(const T& value)
  {
    std::lock_guard<std::mutex> guard(thing_lock_RT_);
    thing_ = value;
  }

  void get(T& ref)
  {
    std::lock_guard<std::mutex> guard(thing_lock_RT_);
    ref = thing_;
  }

private:
  T thing_;
  std::mutex thing_lock_RT_;
};

}  // namespace realtime_tools

#endif  // REALTIME_TOOLS_REALTIME_BOX_H

// racebot's realtime_tools (upstream_compat/realtime_tools): realtime_tools 1.16's header-only API, written for
// racebot. Hands data from a non-realtime thread (a subscriber's callback) to the control loop, which never waits:
// readFromRT swaps the newest data in only when it gets the lock at once.
#ifndef REALTIME_TOOLS_REALTIME_BUFFER_H
#define REALTIME_TOOLS_REALTIME_BUFFER_H

#include <chrono>
#include <memory>
#include <mutex>
#include <thread>

namespace realtime_tools
{

template <class T>
class RealtimeBuffer
{
public:
  RealtimeBuffer() : realtime_data_(new T()), non_realtime_data_(new T()) {}
  explicit RealtimeBuffer(const T& data) : realtime_data_(new T(data)), non_realtime_data_(new T(data)) {}
  RealtimeBuffer(const RealtimeBuffer& source) : realtime_data_(new T()), non_realtime_data_(new T())
  {
    writeFromNonRT(*source.readFromNonRT());
  }
  RealtimeBuffer& operator=(const RealtimeBuffer& source)
  {
    if (this != &source)
      writeFromNonRT(*source.readFromNonRT());
    return *this;
  }

  // The control loop's copy: the newest written data when the lock is free now, else the previous.
  T* readFromRT()
  {
    std::unique_lock<std::mutex> guard(mutex_, std::try_to_lock);
    if (guard.owns_lock() && new_data_available_)
    {
      realtime_data_.swap(non_realtime_data_);
      new_data_available_ = false;
    }
    return realtime_data_.get();
  }

  T* readFromNonRT() const
  {
    std::lock_guard<std::mutex> guard(mutex_);
    return new_data_available_ ? non_realtime_data_.get() : realtime_data_.get();
  }

  void writeFromNonRT(const T& data)
  {
#ifdef NON_POLLING
    std::lock_guard<std::mutex> guard(mutex_);
#else
    // polls rather than blocks, as upstream does: the control loop only ever try-locks
    std::unique_lock<std::mutex> guard(mutex_, std::try_to_lock);
    while (!guard.owns_lock())
    {
      std::this_thread::sleep_for(std::chrono::microseconds(500));
      guard.try_lock();
    }
#endif
    *non_realtime_data_ = data;
    new_data_available_ = true;
  }

  // Sets both copies; only before the control loop runs.
  void initRT(const T& data)
  {
    *non_realtime_data_ = data;
    *realtime_data_ = data;
  }

private:
  std::unique_ptr<T> realtime_data_;
  std::unique_ptr<T> non_realtime_data_;
  bool new_data_available_ = false;
  mutable std::mutex mutex_;
};

}  // namespace realtime_tools

#endif  // REALTIME_TOOLS_REALTIME_BUFFER_H

// racebot's realtime_tools (upstream_compat/realtime_tools): realtime_tools 1.16's header-only API, written for
// racebot. A publisher the control loop fills without waiting: trylock() gives it msg_ when the publishing thread
// has sent the previous one; unlockAndPublish() hands msg_ to that thread, which publishes a copy.
#ifndef REALTIME_TOOLS_REALTIME_PUBLISHER_H
#define REALTIME_TOOLS_REALTIME_PUBLISHER_H

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <ros/node_handle.h>

namespace realtime_tools
{

template <class Msg>
class RealtimePublisher
{
public:
  Msg msg_;  // what the control loop fills while it holds the lock

  RealtimePublisher(const ros::NodeHandle& node, const std::string& topic, int queue_size, bool latched = false)
    : topic_(topic), node_(node)
  {
    construct(queue_size, latched);
  }
  RealtimePublisher() = default;
  RealtimePublisher(const RealtimePublisher&) = delete;
  RealtimePublisher& operator=(const RealtimePublisher&) = delete;

  ~RealtimePublisher()
  {
    stop();
    if (thread_.joinable())
      thread_.join();
    publisher_.shutdown();
  }

  void init(const ros::NodeHandle& node, const std::string& topic, int queue_size, bool latched = false)
  {
    topic_ = topic;
    node_ = node;
    construct(queue_size, latched);
  }

  void stop()
  {
    keep_running_ = false;
    updated_cond_.notify_one();
  }

  // True (holding the lock) when msg_ is the control loop's to fill; never waits.
  bool trylock()
  {
    if (!msg_mutex_.try_lock())
      return false;
    if (turn_ == REALTIME)
      return true;
    msg_mutex_.unlock();
    return false;
  }

  void unlockAndPublish()
  {
    turn_ = NON_REALTIME;
    unlock();
  }

  void lock() { msg_mutex_.lock(); }

  void unlock()
  {
    msg_mutex_.unlock();
    updated_cond_.notify_one();
  }

private:
  void construct(int queue_size, bool latched)
  {
    publisher_ = node_.advertise<Msg>(topic_, queue_size, latched);
    keep_running_ = true;
    turn_ = REALTIME;
    thread_ = std::thread(&RealtimePublisher::publishingLoop, this);
  }

  void publishingLoop()
  {
    while (keep_running_)
    {
      Msg outgoing;
      {
        std::unique_lock<std::mutex> guard(msg_mutex_);
        // woken by unlock() or stop(); the timeout bounds a missed notification
        while (turn_ != NON_REALTIME && keep_running_)
          updated_cond_.wait_for(guard, std::chrono::milliseconds(10));
        if (!keep_running_)
          break;
        outgoing = msg_;
        turn_ = REALTIME;
      }
      publisher_.publish(outgoing);
    }
  }

  enum
  {
    REALTIME,
    NON_REALTIME,
    LOOP_NOT_STARTED
  };

  std::string topic_;
  ros::NodeHandle node_;
  ros::Publisher publisher_;
  std::atomic<bool> keep_running_{false};
  std::thread thread_;
  std::mutex msg_mutex_;  // guards msg_ and turn_
  std::condition_variable updated_cond_;
  std::atomic<int> turn_{LOOP_NOT_STARTED};
};

template <class Msg>
using RealtimePublisherSharedPtr = std::shared_ptr<RealtimePublisher<Msg>>;

}  // namespace realtime_tools

#endif  // REALTIME_TOOLS_REALTIME_PUBLISHER_H

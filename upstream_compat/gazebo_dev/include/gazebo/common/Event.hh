// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): event::EventT and its ConnectionPtr, as a plugin
// uses them (Connect returns a ConnectionPtr; dropping the last copy disconnects).
//
// Beyond upstream, for racebot's plugin host: each connection remembers which plugin made it (the one whose Load,
// Init or callback was running), so that an exception out of a callback is reported with that plugin's name and
// the plugin unloaded, while the other callbacks of the event still run (Gazebo would stop at the exception).
#ifndef GAZEBO_COMMON_EVENT_HH_
#define GAZEBO_COMMON_EVENT_HH_

#include "gazebo/common/CommonTypes.hh"
#include "gazebo/util/bind.hh"
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "gazebo/util/system.hh"

namespace gazebo
{
namespace event
{
namespace detail
{
// The plugin on whose behalf code runs now (0: none); set by racebot's plugin host.
GZ_COMMON_VISIBLE int CurrentOwner();
GZ_COMMON_VISIBLE void SetCurrentOwner(int _owner);
// An exception escaped a callback connected by `_owner`: kept for the host, which unloads that plugin.
GZ_COMMON_VISIBLE void ReportFailure(int _owner, const std::string &_what);
// The failures reported since the last call, emptied.
GZ_COMMON_VISIBLE std::vector<std::pair<int, std::string>> TakeFailures();

// Runs with `_owner` as the current owner, restoring the previous one after.
class OwnerScope
{
public:
  explicit OwnerScope(int _owner) : previous(CurrentOwner()) { SetCurrentOwner(_owner); }
  ~OwnerScope() { SetCurrentOwner(this->previous); }
  OwnerScope(const OwnerScope &) = delete;
  OwnerScope &operator=(const OwnerScope &) = delete;

private:
  int previous;
};
}  // namespace detail

class GZ_COMMON_VISIBLE Event
{
public:
  virtual ~Event() = default;
  virtual void Disconnect(int _id) = 0;
  // Disconnects every callback `_owner` connected (racebot's host, when it unloads a plugin).
  virtual void DisconnectOwner(int _owner) = 0;
  bool GetSignaled() const { return this->signaled; }
  bool Signaled() const { return this->signaled; }
  void SetSignaled(bool _sig) { this->signaled = _sig; }

protected:
  bool signaled = false;
};

// Every event made, so that a plugin's callbacks can be disconnected from all of them.
GZ_COMMON_VISIBLE void RegisterEvent(Event *_event);
GZ_COMMON_VISIBLE void UnregisterEvent(Event *_event);
GZ_COMMON_VISIBLE void DisconnectOwnerEverywhere(int _owner);

class GZ_COMMON_VISIBLE Connection
{
public:
  Connection(std::function<void(int)> _disconnect, int _id) : disconnect(std::move(_disconnect)), id(_id) {}
  ~Connection()
  {
    if (this->disconnect)
      this->disconnect(this->id);
  }
  Connection(const Connection &) = delete;
  Connection &operator=(const Connection &) = delete;
  int Id() const { return this->id; }

private:
  std::function<void(int)> disconnect;
  int id;
};


template<typename T>
class EventT : public Event
{
public:
  EventT() : state(std::make_shared<State>()) { RegisterEvent(this); }
  ~EventT() override { UnregisterEvent(this); }
  EventT(const EventT &) = delete;
  EventT &operator=(const EventT &) = delete;

  ConnectionPtr Connect(const std::function<T> &_subscriber)
  {
    std::lock_guard<std::mutex> lock(this->state->mutex);
    const int id = this->state->nextId++;
    auto slot = std::make_shared<Slot>(Slot{id, detail::CurrentOwner(), _subscriber, true});
    auto slots = std::make_shared<std::vector<std::shared_ptr<Slot>>>(*this->state->slots);
    slots->push_back(slot);
    this->state->slots = slots;
    std::weak_ptr<State> weak = this->state;
    return std::make_shared<Connection>([weak](int _id) {
      if (auto state = weak.lock())
        State::Remove(*state, [_id](const Slot &_s) { return _s.id == _id; });
    }, id);
  }

  void Disconnect(int _id) override
  {
    State::Remove(*this->state, [_id](const Slot &_s) { return _s.id == _id; });
  }

  void DisconnectOwner(int _owner) override
  {
    State::Remove(*this->state, [_owner](const Slot &_s) { return _s.owner == _owner; });
  }

  unsigned int ConnectionCount() const { return this->state->slots->size(); }

  template<typename... Args>
  void operator()(Args &&... _args) { this->Signal(std::forward<Args>(_args)...); }

  template<typename... Args>
  void Signal(Args &&... _args)
  {
    std::shared_ptr<const std::vector<std::shared_ptr<Slot>>> slots;
    {
      std::lock_guard<std::mutex> lock(this->state->mutex);
      slots = this->state->slots;
    }
    this->signaled = true;
    for (const auto &slot : *slots)
    {
      if (!slot->on)
        continue;
      detail::OwnerScope scope(slot->owner);
      try
      {
        slot->callback(_args...);
      }
      catch (const std::exception &_e)
      {
        slot->on = false;
        detail::ReportFailure(slot->owner, _e.what());
      }
      catch (...)
      {
        slot->on = false;
        detail::ReportFailure(slot->owner, "an exception that is not a std::exception");
      }
    }
  }

private:
  struct Slot
  {
    int id;
    int owner;
    std::function<T> callback;
    bool on;
  };
  struct State
  {
    std::mutex mutex;
    int nextId = 0;
    // replaced, never changed in place: a signal walks its own snapshot while callbacks connect or disconnect
    std::shared_ptr<std::vector<std::shared_ptr<Slot>>> slots = std::make_shared<std::vector<std::shared_ptr<Slot>>>();

    template<typename Pred>
    static void Remove(State &_state, Pred _pred)
    {
      std::lock_guard<std::mutex> lock(_state.mutex);
      auto slots = std::make_shared<std::vector<std::shared_ptr<Slot>>>();
      for (const auto &slot : *_state.slots)
      {
        if (_pred(*slot))
          slot->on = false;
        else
          slots->push_back(slot);
      }
      _state.slots = slots;
    }
  };
  std::shared_ptr<State> state;
};
}  // namespace event
}  // namespace gazebo

#endif

// racebot's Gazebo 11 plugin API (upstream_compat/gazebo_dev): event::Events, the simulator's signals. racebot's
// world server fires worldUpdateBegin, beforePhysicsUpdate and worldUpdateEnd at each world update in Gazebo's
// order (World::Update: begin, the models' updates, collision, beforePhysicsUpdate, the physics step, end),
// worldReset on reset_world / reset_simulation, and stop when it stops. The rest exist for plugins that connect
// to them; racebot does not fire them (docs/SUPPORTED.md).
#ifndef GAZEBO_COMMON_EVENTS_HH_
#define GAZEBO_COMMON_EVENTS_HH_

#include <string>

#include <sdf/sdf.hh>

#include "gazebo/common/Console.hh"
#include "gazebo/common/Event.hh"
#include "gazebo/common/UpdateInfo.hh"
#include "gazebo/util/system.hh"

namespace gazebo
{
namespace event
{
class GZ_COMMON_VISIBLE Events
{
#define RACEBOT_GZ_EVENT(Name, member)                                         \
public:                                                                         \
  template<typename T> static ConnectionPtr Connect##Name(T _subscriber)        \
  { return member.Connect(_subscriber); }                                       \
  static void Disconnect##Name(ConnectionPtr _subscriber)                       \
  { if (_subscriber) member.Disconnect(_subscriber->Id()); }

  RACEBOT_GZ_EVENT(Pause, pause)
  RACEBOT_GZ_EVENT(Step, step)
  RACEBOT_GZ_EVENT(Stop, stop)
  RACEBOT_GZ_EVENT(SigInt, sigInt)
  RACEBOT_GZ_EVENT(WorldCreated, worldCreated)
  RACEBOT_GZ_EVENT(CreateEntity, entityCreated)
  RACEBOT_GZ_EVENT(SetSelectedEntity, setSelectedEntity)
  RACEBOT_GZ_EVENT(AddEntity, addEntity)
  RACEBOT_GZ_EVENT(DeleteEntity, deleteEntity)
  RACEBOT_GZ_EVENT(WorldUpdateBegin, worldUpdateBegin)
  RACEBOT_GZ_EVENT(BeforePhysicsUpdate, beforePhysicsUpdate)
  RACEBOT_GZ_EVENT(WorldUpdateEnd, worldUpdateEnd)
  RACEBOT_GZ_EVENT(WorldReset, worldReset)
  RACEBOT_GZ_EVENT(TimeReset, timeReset)
  RACEBOT_GZ_EVENT(PreRender, preRender)
  RACEBOT_GZ_EVENT(Render, render)
  RACEBOT_GZ_EVENT(PostRender, postRender)
  RACEBOT_GZ_EVENT(DiagTimerStart, diagTimerStart)
  RACEBOT_GZ_EVENT(DiagTimerStop, diagTimerStop)
  RACEBOT_GZ_EVENT(RemoveSensor, removeSensor)
  RACEBOT_GZ_EVENT(CreateSensor, createSensor)
#undef RACEBOT_GZ_EVENT

public:
  static EventT<void (bool)> pause;
  static EventT<void ()> step;
  static EventT<void ()> stop;
  static EventT<void ()> sigInt;
  static EventT<void (std::string)> worldCreated;
  static EventT<void (std::string)> entityCreated;
  static EventT<void (std::string, std::string)> setSelectedEntity;
  static EventT<void (std::string)> addEntity;
  static EventT<void (std::string)> deleteEntity;
  static EventT<void (const common::UpdateInfo &)> worldUpdateBegin;
  static EventT<void (const common::UpdateInfo &)> beforePhysicsUpdate;
  static EventT<void ()> worldUpdateEnd;
  static EventT<void ()> worldReset;
  static EventT<void ()> timeReset;
  static EventT<void ()> preRender;
  static EventT<void ()> render;
  static EventT<void ()> postRender;
  static EventT<void (std::string)> diagTimerStart;
  static EventT<void (std::string)> diagTimerStop;
  static EventT<void (std::string)> removeSensor;
  static EventT<void (sdf::ElementPtr, const std::string &, const std::string &, const uint32_t)> createSensor;
};
}  // namespace event
}  // namespace gazebo

#endif

// racebot_sim_bridge's glue: what the hosts of compiled code (gazebo_host, controller_host) share to name, in the
// world server's last line, the compiled code a fatal signal struck. Each host installs its own handler once; the
// handler says what it knows, then PassOn gives the signal to the handler before it (the other host's, Python's
// faulthandler, or the default), so the process ends as it would have.
#ifndef RACEBOT_SIM_BRIDGE_FATAL_SIGNALS_H
#define RACEBOT_SIM_BRIDGE_FATAL_SIGNALS_H

#include <signal.h>
#include <string.h>
#include <unistd.h>

namespace racebot
{
namespace fatal_signals
{
const int kSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
constexpr size_t kCount = sizeof(kSignals) / sizeof(kSignals[0]);

// async-signal-safe: write(2), no allocation
inline void Say(const char *_text) { (void)!write(STDERR_FILENO, _text, strlen(_text)); }

inline const char *Name(int _signal)  // strsignal is not async-signal-safe
{
  switch (_signal)
  {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT";
    default: return "a fatal signal";
  }
}

// One host's place in the chain of handlers (a static of that host's module: pybind11 modules hide their symbols, so
// each has its own).
class Chain
{
public:
  void Install(void (*_handler)(int, siginfo_t *, void *))
  {
    if (this->installed)
      return;
    this->installed = true;
    struct sigaction action;
    memset(&action, 0, sizeof(action));
    action.sa_sigaction = _handler;
    action.sa_flags = SA_SIGINFO | SA_ONSTACK;
    sigemptyset(&action.sa_mask);
    for (size_t i = 0; i < kCount; ++i)
      sigaction(kSignals[i], &action, &this->previous[i]);
  }

  // The handler before this one back in place, and the signal raised again for it.
  void PassOn(int _signal)
  {
    for (size_t i = 0; i < kCount; ++i)
      if (kSignals[i] == _signal)
        sigaction(_signal, &this->previous[i], nullptr);
    raise(_signal);
  }

private:
  struct sigaction previous[kCount];
  bool installed = false;
};
}  // namespace fatal_signals
}  // namespace racebot

#endif  // RACEBOT_SIM_BRIDGE_FATAL_SIGNALS_H

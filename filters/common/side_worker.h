// A second pair of hands for a sequential algorithm: the caller offers one small task
// (a check of a few microseconds), does its own part, and then either finds the task
// done by a thread that serves it, or runs it itself. Serving is lent by a thread that
// would otherwise be idle (the union lends its background thread once that is done), so
// no core is taken from other work, and a server that is busy or descheduled never
// makes the caller wait: a task nobody took is run by the caller. The outcome does not
// depend on who ran a task, provided the task and the caller's part touch different data.
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <type_traits>

namespace mr {

class SideWorker {
public:
  SideWorker() = default;
  SideWorker(const SideWorker&) = delete;
  SideWorker& operator=(const SideWorker&) = delete;

  /// Runs offered tasks on the calling thread until stop() (returns at once after it).
  /// Between offers it runs `idle` (a piece of background work; false once there is
  /// none left), then spins a while (offers come in quick succession) and then naps
  /// between polls.
  void serve(const std::function<bool()>& idle = {});
  /// serve() returns, now or whenever it is called. No task may be pending.
  void stop();

  /// Runs `beside` on the serving thread if it takes it up, `here` on this one; returns
  /// once both have run. `beside` runs here too when nobody took it in time, unless
  /// `here` returned false, which makes `beside` unnecessary (then it may not run).
  /// An exception of either reaches the caller, after `beside` is over (it may use the
  /// caller's data).
  template <class Beside, class Here>
  void run(Beside&& beside, Here&& here) {
    offer(&call<std::remove_reference_t<Beside>>, &beside);
    bool needed = false;
    try {
      needed = here();
    } catch (...) {
      finish(false);
      throw;
    }
    finish(needed);
  }

private:
  template <class F>
  static void call(void* f) {
    (*static_cast<F*>(f))();
  }
  void offer(void (*fn)(void*), void* arg);
  void finish(bool needed);

  enum State : int { kIdle, kOffered, kTaken, kDone };
  std::atomic<int> state_{kIdle};
  void (*fn_)(void*) = nullptr;  // written before kOffered is published
  void* arg_ = nullptr;
  std::exception_ptr error_;  // what the served task threw, published with kDone
  std::atomic<bool> stop_{false};
};

}  // namespace mr

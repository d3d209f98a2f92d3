// Frees large temporaries on another thread while the caller goes on with its last
// steps: destroying a table of a million heap-allocated exact points takes a quarter
// of a second that nothing needs to wait for. destroyer() packs them into a task;
// BackgroundRelease runs it and is joined when it goes out of scope, so nothing
// outlives the call that made it.
#pragma once

#include "common/parallel_for.h"

#include <functional>
#include <memory>
#include <system_error>
#include <thread>
#include <tuple>
#include <utility>

namespace mr {

/// Takes the objects (moved from, left empty) into a task that destroys them when it
/// runs (or when it is dropped), to be run on whichever thread has time.
template <class... T>
std::function<void()> destroyer(T&... objects) {
  auto held = std::make_shared<std::tuple<T...>>(std::move(objects)...);
  return [held]() mutable { held.reset(); };
}

class BackgroundRelease {
public:
  BackgroundRelease() = default;
  BackgroundRelease(const BackgroundRelease&) = delete;
  BackgroundRelease& operator=(const BackgroundRelease&) = delete;
  ~BackgroundRelease() {
    if (thread_.joinable()) thread_.join();
  }

  /// Runs `task` on another thread, or here when one thread is all there is; on that
  /// other thread `then` follows (lending it, see SideWorker), and without one `then`
  /// does not run. Call once.
  void run(std::function<void()> task, std::function<void()> then = {}) {
    if (worker_count() > 1) {
      try {
        thread_ = std::thread([task = std::move(task), then = std::move(then)] {
          task();
          if (then) then();
        });
        return;
      } catch (const std::system_error&) {
        // no thread to be had: run here after all
      }
    }
    task();
  }

private:
  std::thread thread_;
};

}  // namespace mr

// Frees large temporaries on another thread while the caller goes on with its last
// steps: destroying a table of a million heap-allocated exact points takes a quarter
// of a second that nothing needs to wait for. Joined when the releaser goes out of
// scope, so nothing outlives the call that made it.
#pragma once

#include "common/parallel_for.h"

#include <memory>
#include <system_error>
#include <thread>
#include <tuple>
#include <utility>

namespace mr {

class BackgroundRelease {
public:
  BackgroundRelease() = default;
  BackgroundRelease(const BackgroundRelease&) = delete;
  BackgroundRelease& operator=(const BackgroundRelease&) = delete;
  ~BackgroundRelease() {
    if (thread_.joinable()) thread_.join();
  }

  /// Takes the objects (moved from, left empty) and destroys them on another thread,
  /// or here when one thread is all there is. Call once.
  template <class... T>
  void release(T&... objects) {
    auto held = std::make_unique<std::tuple<T...>>(std::move(objects)...);
    if (worker_count() <= 1) return;  // destroyed here, at the end of this call
    std::tuple<T...>* raw = held.get();
    try {
      thread_ = std::thread([raw] { delete raw; });
    } catch (const std::system_error&) {
      return;  // no thread to be had: freed here after all
    }
    held.release();  // the thread owns it now
  }

private:
  std::thread thread_;
};

}  // namespace mr

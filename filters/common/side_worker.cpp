#include "common/side_worker.h"

#include <chrono>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define MR_SPIN_PAUSE() _mm_pause()
#else
#define MR_SPIN_PAUSE() std::this_thread::yield()
#endif

namespace mr {

namespace {
// How long a server spins for the next offer before it naps between polls, and the nap.
// Offers come every few microseconds while the caller checks moves; in its other phases
// a spinning server only took its core's share from the caller (two virtual cores may be
// one physical one). It is never woken: that took the caller a system call per offer,
// more than the checks it hands over.
constexpr auto kSpinFor = std::chrono::microseconds(200);
constexpr auto kNap = std::chrono::microseconds(50);
}  // namespace

void SideWorker::serve(const std::function<bool()>& idle) {
  auto idle_since = std::chrono::steady_clock::now();
  int polls = 0;
  bool napping = false, idle_left = bool(idle);
  while (!stop_.load(std::memory_order_acquire)) {
    int offered = kOffered;
    if (state_.load(std::memory_order_relaxed) == kOffered &&
        state_.compare_exchange_strong(offered, kTaken, std::memory_order_acq_rel)) {
      try {
        fn_(arg_);
      } catch (...) {
        error_ = std::current_exception();  // rethrown to the caller by finish()
      }
      state_.store(kDone, std::memory_order_release);
      napping = false;
      idle_since = std::chrono::steady_clock::now();
      continue;
    }
    if (idle_left) {
      idle_left = idle();
      idle_since = std::chrono::steady_clock::now();
      continue;
    }
    if (napping) {  // (a nap: offers meanwhile are run by the caller)
      std::this_thread::sleep_for(kNap);
      continue;
    }
    MR_SPIN_PAUSE();
    if (++polls % 64 == 0 && std::chrono::steady_clock::now() - idle_since > kSpinFor) napping = true;
  }
}

void SideWorker::stop() { stop_.store(true, std::memory_order_release); }

void SideWorker::offer(void (*fn)(void*), void* arg) {
  fn_ = fn;
  arg_ = arg;
  state_.store(kOffered, std::memory_order_release);
}

void SideWorker::finish(bool needed) {
  int offered = kOffered;
  if (state_.compare_exchange_strong(offered, kIdle, std::memory_order_acq_rel)) {
    if (needed) fn_(arg_);  // nobody took it
    return;
  }
  while (state_.load(std::memory_order_acquire) != kDone) MR_SPIN_PAUSE();
  std::exception_ptr error = std::move(error_);
  error_ = nullptr;
  state_.store(kIdle, std::memory_order_relaxed);
  if (error) std::rethrow_exception(error);
}

}  // namespace mr

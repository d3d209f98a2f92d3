// Deterministic data parallelism for the independent parts of an algorithm: items
// [0, n) are handed out in fixed chunks to the machine's threads. The result does not
// depend on the thread count or on timing as long as fn(i) writes only what belongs
// to item i (callers merge the per-item results in item order afterwards).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace mr {

/// Threads to use: MESHREGRID_THREADS if set (>= 1), else the hardware's.
inline int worker_count() {
  if (const char* env = std::getenv("MESHREGRID_THREADS")) {
    const int n = std::atoi(env);
    if (n >= 1) return n;
  }
  // Read once: the query opens and parses a /sys file (~6 us), and a union asks ~8 times.
  static const int hardware = std::max(1, int(std::thread::hardware_concurrency()));
  return hardware;
}

/// Calls fn(i) for every i in [0, n), chunks of `chunk` items at a time, on up to
/// worker_count() threads (the caller's among them). The first exception thrown by any
/// call is rethrown here after every thread has stopped.
template <class Fn>
void parallel_for(size_t n, size_t chunk, Fn&& fn) {
  chunk = std::max<size_t>(chunk, 1);
  const size_t chunks = (n + chunk - 1) / chunk;
  const int threads = int(std::min<size_t>(size_t(worker_count()), chunks));
  if (threads <= 1) {
    for (size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    try {
      for (size_t c; !failed.load(std::memory_order_relaxed) && (c = next.fetch_add(1)) < chunks;)
        for (size_t i = c * chunk, end = std::min(n, i + chunk); i < end; ++i) fn(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(size_t(threads - 1));
  // A thread that cannot start (a process at its thread limit) is not an error: the
  // threads there are, the caller's among them, take all chunks.
  for (int t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;
    }
  }
  work();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace mr

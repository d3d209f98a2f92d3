// Checks each body before any work: finite, within the filters' range, non-degenerate,
// closed, manifold and consistently oriented; inward-oriented bodies are flipped
// (returned count). Whether a body crosses itself is checked beside the union's sliver
// step (SelfIntersectionCheck).
#pragma once

#include "union/self_intersection.h"
#include "union/surface_union.h"

#include <array>
#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace mr::surface_union {

/// \throw InvalidInput / TopologyError naming the body. Flips inward bodies in place.
int validate_bodies(std::vector<Body>& bodies);

/// The self-intersection part of the validation, run beside the union's sliver step:
/// that step is sequential and leaves the other cores idle, and on CAD plates the check
/// costs a sixth of the union. The caller starts it there and returns the union only
/// after finish(); it also calls finish() before passing on any failure of its own, so a
/// body that crosses itself is reported (the first such body in order) and nothing else
/// is. With one thread (MESHREGRID_THREADS=1) the check
/// runs in the constructor, before any work, and throws there. Keeps a reference to
/// `bodies`, which must outlive it.
class SelfIntersectionCheck {
public:
  explicit SelfIntersectionCheck(const std::vector<Body>& bodies);
  SelfIntersectionCheck(const SelfIntersectionCheck&) = delete;
  SelfIntersectionCheck& operator=(const SelfIntersectionCheck&) = delete;
  ~SelfIntersectionCheck();  // waits for the thread
  /// Starts checking on another thread, which first runs `first` (the union's
  /// temporaries freed there: a third thread beside the sliver step cost the 2000-sphere
  /// cluster more than the check), then `then` (which may check bodies with check_next,
  /// between tasks of its own: it serves the sliver step), and then checks whatever is
  /// left. Without a thread, `first` runs here and `then` not. Call once.
  void start(std::function<void()> first, std::function<void()> then = {});
  /// Checks the next part not taken yet (a range of one body's faces; the body's grid is
  /// built once, by the first thread to take one of its parts); false when none was left.
  bool check_next();
  /// Checks what is left on this thread too, and waits.
  /// \throw TopologyError naming the first body that crosses itself.
  void finish();

private:
  void work();  // takes parts one at a time until none is left
  /// Parts of this many faces: a large body's check is shared out between the threads
  /// (the helper between its sliver-step tasks, this thread in finish()).
  static constexpr int kPartFaces = 8192;
  const std::vector<Body>& bodies_;
  std::vector<size_t> first_part_;  // per body, and one past the last part
  std::vector<std::unique_ptr<SelfIntersectionScan>> scan_;  // per body, built once
  std::unique_ptr<std::once_flag[]> built_;                  // per body
  std::vector<std::optional<std::array<int, 2>>> crossing_;  // per part
  std::vector<std::exception_ptr> error_;                     // per part (out of memory)
  std::atomic<size_t> next_{0};
  std::thread thread_;
};

}  // namespace mr::surface_union

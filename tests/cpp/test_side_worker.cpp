// SideWorker: every offered task runs exactly once, on the server or on the caller; a
// task the caller's part makes unnecessary may be dropped; background work runs between
// tasks until it says none is left; stop() ends serving, also before it began.
#include "common/side_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

namespace {

// Waits up to a second for `flag` (the server's chance to take a task).
void wait_for(const std::atomic<bool>& flag) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (!flag.load() && std::chrono::steady_clock::now() < until) std::this_thread::yield();
}

// Waits up to ten seconds for `count` to reach `n`.
void wait_for_count(const std::atomic<int>& count, int n) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (count.load() < n && std::chrono::steady_clock::now() < until) std::this_thread::yield();
}

}  // namespace

TEST(SideWorker, WithoutAServerTheCallerRunsEverything) {
  mr::SideWorker worker;
  const auto me = std::this_thread::get_id();
  for (int i = 0; i < 100; ++i) {
    std::thread::id beside_on, here_on;
    worker.run([&] { beside_on = std::this_thread::get_id(); },
               [&] {
                 here_on = std::this_thread::get_id();
                 return true;
               });
    EXPECT_EQ(beside_on, me);
    EXPECT_EQ(here_on, me);
  }
}

TEST(SideWorker, EveryTaskOnceAndTheServerTakesSome) {
  auto worker = std::make_unique<mr::SideWorker>();
  std::thread server([&] { worker->serve(); });
  const auto me = std::this_thread::get_id();
  constexpr int kTasks = 2000;
  std::vector<int> ran(kTasks, 0), here_ran(kTasks, 0);
  int on_server = 0;
  for (int i = 0; i < kTasks; ++i) {
    std::atomic<bool> done{false};
    std::thread::id beside_on;
    worker->run(
        [&] {
          ++ran[size_t(i)];
          beside_on = std::this_thread::get_id();
          done = true;
        },
        [&] {
          ++here_ran[size_t(i)];
          if (i % 10 == 0) wait_for(done);  // now and then a caller slow enough to be helped
          return true;
        });
    on_server += beside_on != me;
  }
  worker->stop();
  server.join();
  for (int i = 0; i < kTasks; ++i) {
    ASSERT_EQ(ran[size_t(i)], 1) << i;
    ASSERT_EQ(here_ran[size_t(i)], 1) << i;
  }
  EXPECT_GT(on_server, 0);
}

TEST(SideWorker, AnUnnecessaryTaskRunsAtMostOnce) {
  mr::SideWorker worker;
  std::thread server([&] { worker.serve(); });
  for (int i = 0; i < 500; ++i) {
    int ran = 0;
    worker.run([&] { ++ran; }, [] { return false; });
    ASSERT_LE(ran, 1);
  }
  worker.stop();
  server.join();
}

TEST(SideWorker, StopBeforeServingEndsServingAtOnce) {
  mr::SideWorker worker;
  worker.stop();
  std::thread server([&] { worker.serve(); });
  server.join();  // (a server that kept polling would hang the test here)
  int ran = 0;
  worker.run([&] { ++ran; }, [] { return true; });
  EXPECT_EQ(ran, 1);
}

TEST(SideWorker, BackgroundWorkRunsBetweenTasksUntilNoneIsLeft) {
  mr::SideWorker worker;
  std::atomic<int> pieces{0};
  std::atomic<bool> served{false};
  std::thread server([&] {
    worker.serve([&] { return ++pieces < 50; });
    served = true;
  });
  int ran = 0;
  for (int i = 0; i < 200; ++i) worker.run([&] { ++ran; }, [] { return true; });
  wait_for_count(pieces, 50);
  EXPECT_EQ(ran, 200);
  EXPECT_EQ(pieces.load(), 50);  // not called again after it said none is left
  worker.stop();
  server.join();
  EXPECT_TRUE(served.load());
}

TEST(SideWorker, AnExceptionOfEitherPartReachesTheCaller) {
  mr::SideWorker worker;
  std::thread server([&] { worker.serve(); });
  for (int i = 0; i < 200; ++i) {
    // The task throws, wherever it runs.
    EXPECT_THROW(worker.run([] { throw std::runtime_error("beside"); }, [] { return true; }), std::runtime_error);
    // The caller's part throws: the task is over (or dropped) when the exception arrives.
    std::atomic<int> running{0};
    EXPECT_THROW(worker.run(
                     [&] {
                       ++running;
                       std::this_thread::sleep_for(std::chrono::microseconds(20));
                       --running;
                     },
                     []() -> bool { throw std::logic_error("here"); }),
                 std::logic_error);
    EXPECT_EQ(running.load(), 0);
  }
  // Still serving afterwards.
  int ran = 0;
  worker.run([&] { ++ran; }, [] { return true; });
  EXPECT_EQ(ran, 1);
  worker.stop();
  server.join();
}

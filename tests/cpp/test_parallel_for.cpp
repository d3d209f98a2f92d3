// parallel_for: every item once, the thread count from MESHREGRID_THREADS, errors passed on.
#include "common/parallel_for.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace {

// Sets MESHREGRID_THREADS for one scope.
struct ThreadsEnv {
  explicit ThreadsEnv(const char* n) { setenv("MESHREGRID_THREADS", n, 1); }
  ~ThreadsEnv() { unsetenv("MESHREGRID_THREADS"); }
};

}  // namespace

TEST(ParallelFor, EveryItemExactlyOnceWhateverTheChunkAndThreads) {
  for (const char* threads : {"1", "2", "7"}) {
    ThreadsEnv env(threads);
    EXPECT_EQ(mr::worker_count(), std::atoi(threads));
    for (size_t chunk : {1u, 3u, 1000u}) {
      std::vector<int> hits(10007, 0);
      mr::parallel_for(hits.size(), chunk, [&](size_t i) { hits[i] += int(i % 5) + 1; });
      for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i], int(i % 5) + 1) << threads << " " << chunk;
    }
  }
}

TEST(ParallelFor, NothingToDoCallsNothing) {
  int calls = 0;
  mr::parallel_for(0, 16, [&](size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(ParallelFor, AnExceptionOfAnyItemReachesTheCaller) {
  ThreadsEnv env("4");
  EXPECT_THROW(mr::parallel_for(5000, 10,
                                [](size_t i) {
                                  if (i == 4321) throw std::runtime_error("item 4321");
                                }),
               std::runtime_error);
}

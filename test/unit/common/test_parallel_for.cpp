#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "propulsion_estimator/common/parallel_for.h"

namespace pe = propulsion_estimator;

TEST(ParallelFor, CallsEveryIndexOnceWhateverTheThreads) {
  for (int threads : {-1, 0, 1, 2, 3, 64}) {
    std::vector<std::atomic<int>> calls(101);
    pe::parallelFor(calls.size(), threads, [&](std::size_t i) { ++calls[i]; });
    for (std::size_t i = 0; i < calls.size(); ++i) EXPECT_EQ(calls[i].load(), 1) << "index " << i << ", " << threads << " threads";
  }
  pe::parallelFor(0, 2, [](std::size_t) { FAIL() << "no index to call"; });
}

TEST(ParallelFor, RethrowsTheLowestFailingIndexAfterEveryIndexRan) {
  std::atomic<int> ran{0};
  try {
    pe::parallelFor(50, 3, [&](std::size_t i) {
      ++ran;
      if (i == 31 || i == 17) throw std::runtime_error("index " + std::to_string(i));
    });
    FAIL() << "nothing rethrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "index 17");
  }
  EXPECT_EQ(ran.load(), 50);
}

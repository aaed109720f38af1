// Independent simulated cases run on the machine's cores: the long statistical tests fly tens of
// packs one after another, each case on its own objects, and on two cores take half the time.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace parallel_cases {

// body(i) for every i in [0, count), on up to std::thread::hardware_concurrency() threads; the
// results come back in the order of i, so what a test prints from them and asserts on them does not
// depend on the number of threads. `body` must touch no state shared between cases (gtest's
// assertions are thread-safe).
template <typename Result, typename Body>
std::vector<Result> map(std::size_t count, Body body) {
  std::vector<Result> results(count);
  std::atomic<std::size_t> next{0};
  const auto worker = [&]() {
    for (std::size_t i = next++; i < count; i = next++) results[i] = body(i);
  };
  const std::size_t threads = std::min<std::size_t>(count, std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
  return results;
}

}  // namespace parallel_cases

#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace propulsion_estimator {

/// Calls body(i) once for every i in [0, count), on up to `threads` threads (the calling one
/// among them; fewer than 1 counts as 1), each thread taking the next index as it comes free.
/// Whatever body(i) throws is kept; once every thread has finished, the exception of the lowest
/// such i is rethrown. body must write only what belongs to its own index.
template <typename Body>
void parallelFor(std::size_t count, int threads, Body body) {
  std::vector<std::exception_ptr> failures(count);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        body(i);
      } catch (...) {
        failures[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  const std::size_t extra = std::min<std::size_t>(count, static_cast<std::size_t>(std::max(1, threads))) - (count ? 1 : 0);
  for (std::size_t t = 0; t < extra; ++t) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
}

}  // namespace propulsion_estimator

#pragma once

#include <cstdint>

namespace propulsion_estimator {

/// Count, mean and sum of squared deviations of a set of numbers, updated one at a time (Welford)
/// and merged exactly (Chan, Golub and LeVeque), without the cancellation of sums of squares.
struct RunningMoments {
  std::uint64_t count = 0;  ///< how many numbers
  double mean = 0.0;  ///< their mean
  double m2 = 0.0;  ///< sum of squared deviations from the mean

  /// Adds one number.
  void add(double x) {
    ++count;
    const double delta = x - mean;
    mean += delta / static_cast<double>(count);
    m2 += delta * (x - mean);
  }

  /// Adds the numbers of `other`, as if they had been added one by one.
  void merge(const RunningMoments& other) {
    if (other.count == 0) return;
    if (count == 0) {
      *this = other;
      return;
    }
    const double n = static_cast<double>(count), m = static_cast<double>(other.count);
    const double delta = other.mean - mean;
    mean += delta * m / (n + m);
    m2 += other.m2 + delta * delta * n * m / (n + m);
    count += other.count;
  }

  /// Population variance (divided by count); 0 for fewer than two numbers.
  double variance() const { return count < 2 ? 0.0 : m2 / static_cast<double>(count); }
  /// Sample variance (divided by count - 1); 0 for fewer than two numbers.
  double sampleVariance() const { return count < 2 ? 0.0 : m2 / static_cast<double>(count - 1); }
};

}  // namespace propulsion_estimator

#pragma once

#include <vector>

namespace propulsion_estimator {
namespace gap {

/// One-sided sign-flip permutation test of a mean improvement over independent groups: the share of
/// `permutations` random sign patterns (seeded with `seed`) whose sum reaches the observed one,
/// with the observed pattern counted; 1 when the observed sum is not positive or there is no group.
double signFlipPValue(const std::vector<double>& improvements, int permutations, unsigned seed);

}  // namespace gap
}  // namespace propulsion_estimator

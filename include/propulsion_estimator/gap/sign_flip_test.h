#pragma once

#include <vector>

namespace propulsion_estimator {
namespace gap {

/// One-sided sign-flip permutation test of a mean improvement over independent groups: the share of
/// `permutations` random sign patterns (seeded with `seed`) whose sum reaches the observed one,
/// with the observed pattern counted; 1 when the observed sum is not positive or there is no group.
double signFlipPValue(const std::vector<double>& improvements, int permutations, unsigned seed);

/// The fewest groups with which the exact sign-flip test can reach p < `significance` (in (0, 1)):
/// with G groups the observed sign pattern alone has probability 2^-G, so G must exceed
/// log2(1 / significance); 7 for 0.01.
int fewestGroupsForSignificance(double significance);

}  // namespace gap
}  // namespace propulsion_estimator

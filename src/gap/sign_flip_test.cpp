#include "propulsion_estimator/gap/sign_flip_test.h"

#include <cmath>
#include <random>

namespace propulsion_estimator {
namespace gap {

double signFlipPValue(const std::vector<double>& improvements, int permutations, unsigned seed) {
  if (improvements.empty()) return 1.0;
  double observed = 0.0;
  for (double d : improvements) observed += d;
  if (observed <= 0.0) return 1.0;
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution flip(0.5);
  int reached = 0;
  for (int i = 0; i < permutations; ++i) {
    double sum = 0.0;
    for (double d : improvements) sum += flip(rng) ? d : -d;
    if (sum >= observed) ++reached;
  }
  return (1.0 + reached) / (1.0 + permutations);
}

int fewestGroupsForSignificance(double significance) {
  int groups = 1;
  while (std::ldexp(1.0, -groups) >= significance) ++groups;
  return groups;
}

}  // namespace gap
}  // namespace propulsion_estimator

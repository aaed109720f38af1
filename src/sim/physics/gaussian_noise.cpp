#include "propulsion_estimator/sim/physics/gaussian_noise.h"

namespace propulsion_estimator {
namespace sim {

double gaussianNoise(double sigma, std::mt19937_64& rng) {
  return sigma > 0.0 ? std::normal_distribution<double>(0.0, sigma)(rng) : 0.0;
}

}  // namespace sim
}  // namespace propulsion_estimator

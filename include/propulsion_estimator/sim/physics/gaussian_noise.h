#pragma once

#include <random>

namespace propulsion_estimator {
namespace sim {

/// One draw of zero-mean Gaussian noise with standard deviation `sigma` from `rng`; 0, drawing
/// nothing, when sigma is not positive (a noise-free sensor leaves the random stream alone).
double gaussianNoise(double sigma, std::mt19937_64& rng);

}  // namespace sim
}  // namespace propulsion_estimator

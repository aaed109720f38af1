#include "propulsion_estimator/gap/effect_fit.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <Eigen/Dense>

namespace propulsion_estimator {
namespace gap {
namespace {

Eigen::VectorXd residuals(const ThrustViews& views, const std::vector<const Block*>& blocks,
                          const effects::ModelEffects& effects) {
  Eigen::VectorXd r(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) r[i] = relative(views.pwmView(*blocks[i], effects), *blocks[i]);
  return r;
}

effects::ModelEffects withParameters(const effects::ModelEffects& references, const std::vector<effects::Kind>& kinds,
                                     const Eigen::VectorXd& theta) {
  effects::ModelEffects effects = references;
  for (std::size_t k = 0; k < kinds.size(); ++k) effects.setParameter(kinds[k], theta[k]);
  return effects;
}

}  // namespace

EffectFit fitEffects(const ThrustViews& views, const std::vector<const Block*>& blocks,
                     const std::vector<effects::Kind>& kinds, const effects::ModelEffects& references) {
  EffectFit fit;
  fit.kinds = kinds;
  const int p = static_cast<int>(kinds.size());
  Eigen::VectorXd theta(p), lo(p), hi(p), step(p);
  for (int k = 0; k < p; ++k) {
    const effects::ParameterSpec& spec = effects::parameterSpec(kinds[k]);
    theta[k] = spec.neutral;
    lo[k] = spec.min;
    hi[k] = spec.max;
    step[k] = 1e-4 * (spec.max - spec.min);
  }
  Eigen::VectorXd r = residuals(views, blocks, withParameters(references, kinds, theta));
  double cost = r.squaredNorm();
  Eigen::MatrixXd jacobian(blocks.size(), p);
  double lambda = 1e-3;
  auto computeJacobian = [&]() {
    for (int k = 0; k < p; ++k) {
      Eigen::VectorXd shifted = theta;
      // Step inwards at a bound so that the difference stays in range.
      const double h = theta[k] + step[k] <= hi[k] ? step[k] : -step[k];
      shifted[k] += h;
      jacobian.col(k) = (residuals(views, blocks, withParameters(references, kinds, shifted)) - r) / h;
    }
  };
  for (int iteration = 0; iteration < 40 && p > 0; ++iteration) {
    computeJacobian();
    const Eigen::MatrixXd jtj = jacobian.transpose() * jacobian;
    const Eigen::VectorXd jtr = jacobian.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Eigen::MatrixXd damped = jtj;
      damped.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
      Eigen::VectorXd candidate = theta - damped.ldlt().solve(jtr);
      candidate = candidate.cwiseMax(lo).cwiseMin(hi);
      const Eigen::VectorXd r_candidate = residuals(views, blocks, withParameters(references, kinds, candidate));
      const double cost_candidate = r_candidate.squaredNorm();
      if (cost_candidate < cost) {
        const double gain = cost - cost_candidate;
        theta = candidate;
        r = r_candidate;
        cost = cost_candidate;
        lambda = std::max(lambda / 10.0, 1e-9);
        improved = true;
        if (gain < 1e-12 * std::max(cost, 1e-12)) iteration = 40;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) break;
  }
  fit.effects = withParameters(references, kinds, theta);
  const int n = static_cast<int>(blocks.size());
  fit.rms_relative = n > 0 ? std::sqrt(cost / n) : 0.0;
  fit.ci_half.assign(p, 0.0);
  if (p > 0 && n > p) {
    computeJacobian();
    std::set<std::pair<int, int>> groups;
    for (const Block* block : blocks) groups.insert({block->flight, block->group});
    const double inflation = static_cast<double>(n) / std::max<std::size_t>(groups.size(), 1);
    const double variance = cost / (n - p) * inflation;
    const Eigen::MatrixXd covariance =
        (jacobian.transpose() * jacobian).completeOrthogonalDecomposition().pseudoInverse() * variance;
    for (int k = 0; k < p; ++k) fit.ci_half[k] = 1.96 * std::sqrt(std::max(covariance(k, k), 0.0));
  }
  return fit;
}

}  // namespace gap
}  // namespace propulsion_estimator

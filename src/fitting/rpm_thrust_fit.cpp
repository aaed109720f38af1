#include "propulsion_estimator/fitting/rpm_thrust_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "propulsion_estimator/common/data_error.h"

namespace propulsion_estimator {
namespace {

constexpr int kMinRows = 10;
// A pivot below this share of the largest: the rows do not tell the two terms apart (one speed).
constexpr double kRelativePivot = 1e-12;

}  // namespace

RpmThrust fitRpmThrust(const std::vector<BenchLog>& logs, double bench_air_density_kg_m3) {
  const std::string source = logs.empty() ? std::string("bench logs") : logs.front().source;
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  double sum_t2 = 0.0;
  int rows = 0;
  bool any_rpm = false;
  for (const BenchLog& log : logs) {
    if (!log.has(BenchColumn::kRpm) || !log.has(BenchColumn::kThrust)) continue;
    any_rpm = true;
    const std::vector<double>& rpm = log.column(BenchColumn::kRpm);
    const std::vector<double>& thrust = log.column(BenchColumn::kThrust);
    for (std::size_t i = 0; i < log.rows(); ++i) {
      if (!(rpm[i] > 0.0) || !std::isfinite(rpm[i]) || !std::isfinite(thrust[i])) continue;
      // Scaled to kilo-rpm so that the normal equations stay well conditioned.
      const Eigen::Vector2d phi(rpm[i] * rpm[i] * 1e-6, rpm[i] * 1e-3);
      normal += phi * phi.transpose();
      rhs += phi * thrust[i];
      sum_t2 += thrust[i] * thrust[i];
      ++rows;
    }
  }
  if (!any_rpm) throw DataError(source + ": no rpm column: thrust from rpm cannot be fitted");
  if (rows < kMinRows) {
    throw DataError(source + ": " + std::to_string(rows) + " rows with rpm and thrust, fewer than " +
                    std::to_string(kMinRows) + ": thrust from rpm cannot be fitted");
  }
  const Eigen::LDLT<Eigen::Matrix2d> ldlt(normal);
  const Eigen::Vector2d pivots = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(pivots.minCoeff() > kRelativePivot * pivots.maxCoeff())) {
    throw DataError(source + ": the rows with rpm and thrust are all at one speed: thrust from rpm cannot be fitted");
  }
  const Eigen::Vector2d scaled = ldlt.solve(rhs);
  RpmThrust result;
  result.n_per_rpm2 = scaled(0) * 1e-6;
  result.n_per_rpm = scaled(1) * 1e-3;
  result.bench_air_density_kg_m3 = bench_air_density_kg_m3;
  result.rows = rows;
  // Residual sum of squares from the normal equations: sum t^2 - 2 theta.rhs + theta' N theta.
  const double rss = sum_t2 - 2.0 * scaled.dot(rhs) + scaled.dot(normal * scaled);
  result.rms_n = std::sqrt(std::max(0.0, rss) / rows);
  return result;
}

}  // namespace propulsion_estimator

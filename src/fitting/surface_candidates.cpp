#include "propulsion_estimator/fitting/surface_candidates.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

constexpr int kPwmPoints = 36;
constexpr int kVoltagePoints = 15;
constexpr double kBandShare = 0.25;

double gridValue(double lo, double hi, int k, int n) { return lo + (hi - lo) * k / (n - 1); }

// Visits the covered grid: f(x, v, value, value at the next PWM or NaN, value at the next voltage or NaN).
template <typename Visit>
void visitGrid(const ResponseSurface& surface, const ModelDomain& domain, Visit visit) {
  double values[kPwmPoints][kVoltagePoints];
  bool inside[kPwmPoints][kVoltagePoints];
  for (int a = 0; a < kPwmPoints; ++a) {
    const double x = gridValue(domain.pwm_min_us, domain.pwm_max_us, a, kPwmPoints);
    for (int b = 0; b < kVoltagePoints; ++b) {
      const double v = gridValue(domain.voltage_min_v, domain.voltage_max_v, b, kVoltagePoints);
      inside[a][b] = domain.contains(x, v);
      values[a][b] = inside[a][b] ? surface.evaluate(x, v) : kNaN;
    }
  }
  for (int a = 0; a < kPwmPoints; ++a) {
    for (int b = 0; b < kVoltagePoints; ++b) {
      if (!inside[a][b]) continue;
      const double next_pwm = a + 1 < kPwmPoints ? values[a + 1][b] : kNaN;
      const double next_voltage = b + 1 < kVoltagePoints ? values[a][b + 1] : kNaN;
      visit(values[a][b], next_pwm, next_voltage);
    }
  }
}

// The value a candidate is judged by: the worst of its determined scores.
double worstScore(const CandidateScore& s) {
  double worst = -std::numeric_limits<double>::infinity();
  for (double score : {s.held_out_rmse, s.low_band_rmse, s.high_band_rmse}) {
    if (std::isfinite(score)) worst = std::max(worst, score);
  }
  return worst;
}

}  // namespace

std::vector<VoltageBand> voltageBandOfLevels(const BenchDataset& data, VoltageBands* bands) {
  const std::vector<Level>& levels = data.voltage_levels;
  const double lo = levels.front().centre, hi = levels.back().centre;
  std::vector<VoltageBand> band(levels.size(), VoltageBand::kMiddle);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    if (k == 0 || levels[k].centre <= lo + kBandShare * (hi - lo)) band[k] = VoltageBand::kLow;
    if (k + 1 == levels.size() || levels[k].centre >= hi - kBandShare * (hi - lo)) band[k] = VoltageBand::kHigh;
  }
  const double inf = std::numeric_limits<double>::infinity();
  *bands = VoltageBands{inf, -inf, inf, inf, -inf};
  for (std::size_t row = 0; row < data.rows(); ++row) {
    const double v = data.voltage_v[row];
    const VoltageBand b = band[data.voltage_level[row]];
    if (b == VoltageBand::kLow) {
      bands->low_min_v = std::min(bands->low_min_v, v);
      bands->low_max_v = std::max(bands->low_max_v, v);
    } else {
      bands->rest_min_v = std::min(bands->rest_min_v, v);
    }
    if (b == VoltageBand::kHigh) {
      bands->high_min_v = std::min(bands->high_min_v, v);
      bands->high_max_v = std::max(bands->high_max_v, v);
    }
  }
  return band;
}

bool isNonDecreasing(const ResponseSurface& surface, const ModelDomain& domain, double tolerance) {
  bool rising = true;
  visitGrid(surface, domain, [&](double value, double next_pwm, double next_voltage) {
    if (next_pwm < value - tolerance || next_voltage < value - tolerance) rising = false;
  });
  return rising;
}

int unphysicalCells(const ResponseSurface& surface, const ModelDomain& domain, double tolerance) {
  int cells = 0;
  visitGrid(surface, domain, [&](double value, double next_pwm, double next_voltage) {
    cells += value < -tolerance || next_pwm < value - tolerance || next_voltage < value - tolerance;
  });
  return cells;
}

std::vector<SurfaceCandidate> driveCurveCandidates(const FitRows& rows) {
  std::vector<SurfaceCandidate> candidates;
  const double pwm_full_us = findFullThrottle(rows);
  const bool full_throttle = std::isfinite(pwm_full_us);
  const std::vector<std::optional<DriveCurveFit>> fits = fitDriveCurves(rows, pwm_full_us);
  for (int degree = 1; degree <= DriveCurve::kMaxDegree; ++degree) {
    SurfaceCandidate candidate;
    candidate.score.basis = "drive_curve";
    candidate.score.full_throttle = full_throttle;
    candidate.score.pwm_degree = candidate.score.voltage_degree = degree;
    candidate.score.terms = degree + (full_throttle ? 3 : 2);
    candidate.score.held_out_rmse = candidate.score.low_band_rmse = candidate.score.high_band_rmse = kNaN;
    if (const std::optional<DriveCurveFit>& fit = fits[degree - 1]) {
      candidate.score.held_out_rmse = fit->held_out_rmse;
      candidate.score.low_band_rmse = fit->low_band_rmse;
      candidate.score.high_band_rmse = fit->high_band_rmse;
      candidate.surface = ResponseSurface(fit->curve);
      candidate.drive_fit = fit;
    }
    candidates.push_back(std::move(candidate));
  }
  return candidates;
}

const SurfaceCandidate* chooseCandidate(const std::vector<SurfaceCandidate>& candidates, double parsimony) {
  auto eligible = [](const SurfaceCandidate& c) {
    return c.surface && c.score.physical && std::isfinite(c.score.held_out_rmse);
  };
  double best = std::numeric_limits<double>::infinity();
  for (const SurfaceCandidate& c : candidates) {
    if (eligible(c)) best = std::min(best, worstScore(c.score));
  }
  const SurfaceCandidate* chosen = nullptr;
  for (const SurfaceCandidate& c : candidates) {
    if (!eligible(c) || !(worstScore(c.score) <= best * (1.0 + parsimony))) continue;
    if (!chosen || c.score.terms < chosen->score.terms ||
        (c.score.terms == chosen->score.terms && worstScore(c.score) < worstScore(chosen->score))) {
      chosen = &c;
    }
  }
  return chosen;
}

}  // namespace fitting
}  // namespace propulsion_estimator

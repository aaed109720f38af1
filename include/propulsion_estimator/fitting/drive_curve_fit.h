#pragma once

#include <optional>
#include <vector>

#include "propulsion_estimator/model/drive_curve.h"

namespace propulsion_estimator {
namespace fitting {

/// Where a row sits for the extrapolation scores: the lowest voltage band, the highest, or between.
enum class VoltageBand {
  kMiddle = 0,  ///< neither band
  kLow = 1,     ///< the lowest voltage levels
  kHigh = 2,    ///< the highest voltage levels
};
constexpr int kVoltageBandCount = 3;  ///< number of VoltageBand values
static_assert(static_cast<int>(VoltageBand::kHigh) + 1 == kVoltageBandCount, "kVoltageBandCount");

/// The rows of one output, each with its cross-validation group and voltage band.
struct FitRows {
  std::vector<double> pwm_us;     ///< per row, us
  std::vector<double> voltage_v;  ///< per row, V
  std::vector<double> y;          ///< per row, the output in its file unit
  std::vector<int> group;         ///< per row, its cross-validation group (0..groups - 1)
  std::vector<VoltageBand> band;  ///< per row, its voltage band
  int groups = 0;                 ///< number of cross-validation groups

  /// Number of rows.
  std::size_t size() const { return y.size(); }
};

/// A drive curve fitted with non-negative coefficients (drive_curve.h), and its held-out errors in
/// the output's unit: one group out at a time (pooled), the lowest voltage band fitted on the rest,
/// the highest likewise. NaN where a fold leaves too few rows or drive levels.
struct DriveCurveFit {
  DriveCurve curve{0.0, {0.0}};  ///< fitted on the subsample
  double held_out_rmse = 0.0;    ///< one group out at a time, pooled
  double low_band_rmse = 0.0;    ///< the lowest voltage band, fitted on the rest
  double high_band_rmse = 0.0;   ///< the highest voltage band, fitted on the rest
  double scale = 1.0;  ///< of u in the fit's basis t = u / scale (keeps the normal equations sane)
};

/// The ESC's full-throttle end point x1 in `rows`, us: the PWM above which the output stops rising,
/// so that u = min(max(0, PWM - x0), x1 - x0) / 1000 * V. Looked for between an eighth and half of
/// the PWM span below its top, only where rows at two PWM values or more lie above it (a plateau the
/// bench logged), and taken only when it cuts a cubic drive curve's squared error by a third and is
/// significant (F statistic 20 or more); else DriveCurve::kNoFullThrottle. Throws nothing.
double findFullThrottle(const FitRows& rows);

/// Fits y = sum_k c_k u^k for each degree 1..DriveCurve::kMaxDegree (element degree - 1), c_k >= 0,
/// u = min(max(0, PWM - x0), pwm_full_us - x0) / 1000 * V, with x0 the PWM at which the rotor
/// starts, chosen on each fold's training rows by least squares over a grid, on an even subsample of
/// at most 20000 rows (refit the chosen one with refitOnAllRows); pwm_full_us as findFullThrottle
/// found it on all rows, or DriveCurve::kNoFullThrottle. nullopt for a degree the rows cannot
/// determine (fewer rows than coefficients + 2, x1 counted).
std::vector<std::optional<DriveCurveFit>> fitDriveCurves(const FitRows& rows, double pwm_full_us);

/// `fit`'s curve with its x0 and x1 and the coefficients refitted (c_k >= 0) on every row; `fit`'s
/// own curve when that fit is singular. Throws nothing.
DriveCurve refitOnAllRows(const FitRows& rows, const DriveCurveFit& fit);

}  // namespace fitting
}  // namespace propulsion_estimator

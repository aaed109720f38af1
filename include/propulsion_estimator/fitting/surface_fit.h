#pragma once

#include <array>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "propulsion_estimator/fitting/bench_dataset.h"
#include "propulsion_estimator/fitting/fit_options.h"
#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace fitting {

/// One candidate surface and its cross-validated errors (NaN: not determined by the data when
/// those rows are held out): a polyXY degree pair, or a drive curve (drive_curve.h) whose degree in
/// u is given as both degrees.
struct CandidateScore {
  int pwm_degree = 0;      ///< PWM degree (a drive curve's degree in u)
  int voltage_degree = 0;  ///< voltage degree (a drive curve's degree in u)
  int terms = 0;           ///< coefficients; a drive curve's x0, and x1 when fitted, count as one each
  /// RMSE predicting each held-out group, in the output's file unit; NaN when not determined
  double held_out_rmse = 0.0;
  std::string basis = "polynomial";  ///< or "drive_curve"
  double low_band_rmse = 0.0;        ///< fitted above the lowest voltage band, judged on it
  double high_band_rmse = 0.0;       ///< fitted below the highest voltage band, judged on it
  /// Non-decreasing in PWM and in voltage over the covered domain (always for a drive curve;
  /// efficiency, which need not be, counts as physical).
  bool physical = true;
  bool full_throttle = false;  ///< a drive curve with the ESC's full-throttle end point fitted
};

/// The voltage bands of the extrapolation scores: fitted above the lowest, judged on it (and the
/// same for the highest). Levels whose centre lies in the lowest quarter of the span of level centres
/// form the low band (the lowest level alone with two levels), the highest quarter the high band.
struct VoltageBands {
  double low_min_v = 0.0;   ///< lowest voltage of the low band's rows, V
  double low_max_v = 0.0;   ///< highest voltage of the low band's rows, V
  double rest_min_v = 0.0;  ///< the lowest row voltage above the low band (fitted on), V
  double high_min_v = 0.0;  ///< lowest voltage of the high band's rows, V
  double high_max_v = 0.0;  ///< highest voltage of the high band's rows, V
};

/// How well each output matches the bench data, in its file unit. For a surface also the chosen
/// degrees and every candidate's held-out error.
struct OutputFitReport {
  Output output = Output::kThrust;  ///< which output
  OutputSource source = OutputSource::kNone;  ///< surface, derived or none
  std::string unit;  ///< file unit of the figures (g, A, W, g/W, rpm)
  int points = 0;  ///< samples compared (for a derived output too)
  double r2 = 0.0;  ///< coefficient of determination
  double rmse = 0.0;  ///< root mean square error
  double max_error = 0.0;  ///< largest absolute error
  std::vector<CandidateScore> candidates;  ///< surfaces only
  std::string left_out;                    ///< why a poorly fitting output was left out, else empty
};

/// The result of fitBenchModel: the model, whether it may be written, the data it was fitted on and
/// how well each output matches it.
struct BenchFit {
  PropulsionModel model;  ///< the fitted model
  /// Empty when the model passes the loader's grid check (model_validation.h); otherwise why
  /// not: such a model must not be written. When current, power or rpm fails, it adds that
  /// --without that output writes the rest.
  std::string validation_error;
  BenchDataset data;  ///< the rows it was fitted on
  FitGrouping grouping = FitGrouping::kVoltageLevel;  ///< the one used (never kAuto)
  std::string grouping_description;  ///< the grouping in words, for the report
  std::array<OutputFitReport, kOutputCount> outputs;  ///< one per Output
  std::vector<std::string> notes;  ///< data notes, then what the fit decided (metadata, grouping)
  double parsimony = 0.0;          ///< FitOptions::parsimony the degrees were chosen with
  VoltageBands bands;              ///< of the extrapolation scores
};

/// An output (other than thrust) whose surface explains less of its column than this is left out.
constexpr double kPoorFitR2 = 0.9;

/// Fits the model: per output the physical candidate (non-decreasing in PWM and voltage over the
/// covered domain) with the least held-out error, the worst of leave-one-group-out and the two
/// voltage-band extrapolations, among drive curves of degree 1 to 3 and polyXY degrees up to the
/// option's maxima (on inputs centred and scaled to [-1, 1] over the data's domain). The domain
/// records the voltage range covered at each PWM level. Current, power or rpm whose chosen surface
/// explains less than kPoorFitR2 of its column is left out, with a note saying why. Throws
/// DataError when the data cannot determine a surface (one voltage level, fewer than 3 PWM
/// levels, too few points, a constant output), when the logs contradict each other's metadata, and
/// when neither the logs nor the options give the bench air or the supply, naming every one missing.
BenchFit fitBenchModel(const std::vector<BenchLog>& logs, const FitOptions& options);

}  // namespace fitting
}  // namespace propulsion_estimator

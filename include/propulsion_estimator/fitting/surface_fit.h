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

/// One candidate degree pair and its cross-validated error (NaN: not determined by the data when
/// a group is held out).
struct CandidateScore {
  int pwm_degree = 0;  ///< PWM degree
  int voltage_degree = 0;  ///< voltage degree
  int terms = 0;  ///< number of polynomial terms
  /// RMSE predicting each held-out group, in the output's file unit; NaN when not determined
  double held_out_rmse = 0.0;
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
};

/// Fits the model: per output the polyXY degrees (up to the option's maxima) with the least
/// held-out error, on inputs centred and scaled to [-1, 1] over the data's domain. Throws
/// DataError when the data cannot determine a surface (one voltage level, fewer than 3 PWM
/// levels, too few points, a constant output), when the logs contradict each other's metadata, and
/// when neither the logs nor the options give the bench air or the supply, naming every one missing.
BenchFit fitBenchModel(const std::vector<BenchLog>& logs, const FitOptions& options);

}  // namespace fitting
}  // namespace propulsion_estimator

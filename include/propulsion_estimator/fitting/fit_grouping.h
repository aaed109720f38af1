#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/fitting/bench_dataset.h"
#include "propulsion_estimator/fitting/fit_options.h"

namespace propulsion_estimator {
namespace fitting {

/// How rows are grouped for cross-validation, resolved from FitOptions::grouping: the kind used
/// (never kAuto), each row's group, the groups' names for messages and a description for reports.
struct Grouping {
  FitGrouping kind = FitGrouping::kVoltageLevel;  ///< never kAuto
  bool chosen_automatically = false;              ///< kAuto was asked for
  std::vector<int> group_of_row;                  ///< per row of the dataset
  std::vector<std::string> group_names;  ///< "the 11.06 V level", "the 1500 us level", a log's source
  std::string description;  ///< "leave one voltage level out (8 levels, ...)"

  /// Number of groups.
  int groups() const { return static_cast<int>(group_names.size()); }
};

/// Resolves `requested` on `data`: kAuto is voltage levels when there are 3 or more, else PWM
/// levels. Throws nothing.
Grouping resolveGrouping(const BenchDataset& data, FitGrouping requested);

/// The --group-by option that gave `grouping`, for messages: "--group-by pwm", "--group-by auto (by voltage)".
std::string groupingFlag(const Grouping& grouping);

}  // namespace fitting
}  // namespace propulsion_estimator

#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/fitting/fit_options.h"
#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace fitting {

/// The metadata a fitted model records, from the options, else the logs' "# key: value" lines,
/// else (bench air) the mean of their ambient_temp_c / pressure_pa columns. A missing esc, motor or
/// propeller name is recorded as "unknown" with a note in `notes`, as is a mean over differing
/// logs. Throws DataError when the logs disagree on a text value, when a number or the supply does
/// not parse, when the bench air or the supply is given nowhere (every one missing named at once),
/// and when the bench air is one the model loader would refuse (naming where it came from).
ModelMetadata resolveBenchMetadata(const std::vector<BenchLog>& logs, const FitOptions& options,
                                   std::vector<std::string>* notes);

}  // namespace fitting
}  // namespace propulsion_estimator

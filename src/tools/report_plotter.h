#pragma once

#include <string>

namespace propulsion_estimator {

// Runs scripts/plot_bench_report.py (`mode` "fit" or "compare") on a report directory. The
// script is `script` when given, else the one installed next to this executable
// (/proc/self/exe). Throws ConfigError when the script is missing, when `python` cannot import
// matplotlib, or when the script fails.
void runPlotScript(const std::string& mode, const std::string& directory, const std::string& python,
                   const std::string& script);

}  // namespace propulsion_estimator

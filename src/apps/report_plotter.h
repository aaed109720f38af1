#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace propulsion_estimator {

// Draws a report's figures with scripts/plot_bench_report.py and matplotlib; --python and
// --plot-script choose the interpreter and the script (default: python3, and the script installed
// next to this executable, found through /proc/self/exe).
class ReportPlotter {
 public:
  void addTo(CLI::App& app);
  // Throws ConfigError when the script is missing or the interpreter cannot import matplotlib,
  // saying what to do. The tools call it before their work, so that it is not lost.
  void check() const;
  // Runs the script in `mode` ("fit" or "compare") on a report directory. Throws ConfigError as
  // check() does, or when the script fails.
  void plot(const std::string& mode, const std::string& directory) const;

 private:
  std::string python_ = "python3";
  std::string script_;
};

}  // namespace propulsion_estimator

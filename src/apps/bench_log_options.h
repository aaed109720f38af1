#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log_reader.h"

namespace propulsion_estimator {

// The log-reading options both tools share (--thrust-sign, --current-sign, --map, --decimal).
class BenchLogOptions {
 public:
  void addTo(CLI::App& app);
  // The reader options; ConfigError for a --map that names no quantity.
  BenchReadOptions readOptions() const;

 private:
  std::string thrust_sign_ = "auto";
  std::string current_sign_ = "auto";
  std::vector<std::string> maps_;
  std::string decimal_ = "auto";
};

// Reads every log once; a directory argument stands for its *.csv files. A file named twice
// carries a note saying so.
std::vector<BenchLog> readBenchLogs(const std::vector<std::string>& arguments, const BenchReadOptions& options);

}  // namespace propulsion_estimator

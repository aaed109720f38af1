#include "propulsion_estimator/core/bench_csv.h"

#include <cstdio>
#include <fstream>

#include "propulsion_estimator/core/config_error.h"
#include "propulsion_estimator/core/units.h"

namespace propulsion_estimator {

const char* benchColumnName(BenchColumn column) {
  static const char* const kNames[kBenchColumnCount] = {"time_s",  "pwm_us", "voltage_v",      "thrust_n",
                                                        "current_a", "power_w", "rpm", "ambient_temp_c",
                                                        "motor_temp_c", "pressure_pa"};
  return kNames[static_cast<int>(column)];
}

void writeNativeBenchCsv(const BenchLog& log, std::ostream& out, ThrustUnit thrust_unit) {
  for (const auto& [key, value] : log.metadata) out << "# " << key << ": " << value << "\n";
  std::vector<int> logged;
  for (int c = 0; c < kBenchColumnCount; ++c) {
    if (!log.columns[c].empty()) logged.push_back(c);
  }
  for (std::size_t k = 0; k < logged.size(); ++k) {
    const auto column = static_cast<BenchColumn>(logged[k]);
    out << (k ? "," : "")
        << (column == BenchColumn::kThrust && thrust_unit == ThrustUnit::kGram ? "thrust_g" : benchColumnName(column));
  }
  out << "\n";
  char buffer[32];
  for (std::size_t row = 0; row < log.rows(); ++row) {
    for (std::size_t k = 0; k < logged.size(); ++k) {
      double value = log.columns[logged[k]][row];
      if (logged[k] == static_cast<int>(BenchColumn::kThrust) && thrust_unit == ThrustUnit::kGram) {
        value /= kNewtonPerGramForce;
      }
      std::snprintf(buffer, sizeof(buffer), "%.6g", value);
      out << (k ? "," : "") << buffer;
    }
    out << "\n";
  }
}

void saveNativeBenchCsv(const BenchLog& log, const std::string& path, ThrustUnit thrust_unit) {
  std::ofstream file(path);
  if (!file) throw ConfigError(path + ": cannot open for writing");
  writeNativeBenchCsv(log, file, thrust_unit);
  if (!file) throw ConfigError(path + ": cannot write");
}

}  // namespace propulsion_estimator

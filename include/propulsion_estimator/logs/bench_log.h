#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace propulsion_estimator {

/// The quantities a thrust stand logs, in SI (thrust in N) except PWM (us), rpm and deg C.
enum class BenchColumn {
  kTime = 0,     ///< time_s
  kPwm,          ///< pwm_us
  kVoltage,      ///< voltage_v
  kThrust,       ///< thrust_n (files may give thrust_g)
  kCurrent,      ///< current_a
  kPower,        ///< power_w
  kRpm,          ///< rpm
  kAmbientTemp,  ///< ambient_temp_c
  kMotorTemp,    ///< motor_temp_c
  kPressure,     ///< pressure_pa
};
constexpr int kBenchColumnCount = 10;  ///< number of BenchColumn values
static_assert(static_cast<int>(BenchColumn::kPressure) + 1 == kBenchColumnCount, "kBenchColumnCount counts every BenchColumn");
/// The native CSV name of a column ("pwm_us", ...; thrust is "thrust_n").
const char* benchColumnName(BenchColumn column);

/// One thrust-stand log, column-wise. A column that was not logged is empty; a logged one has
/// one value per row.
struct BenchLog {
  std::string source;                           ///< file it came from, for messages and reports
  std::map<std::string, std::string> metadata;  ///< "# key: value" lines of a native file
  std::array<std::vector<double>, kBenchColumnCount> columns;  ///< one vector per BenchColumn, empty when not logged
  std::vector<int> line_numbers;  ///< file line of each row
  /// Columns the package does not use, kept for reports: name -> one text value per row.
  std::map<std::string, std::vector<std::string>> extra_columns;
  /// What the reader decided about ambiguous content (a negated thrust, the rpm column it took),
  /// one sentence each, for the reports.
  std::vector<std::string> notes;

  /// Number of rows.
  std::size_t rows() const { return line_numbers.size(); }
  /// Whether `column` was logged.
  bool has(BenchColumn column) const { return !columns[static_cast<int>(column)].empty(); }
  /// The values of `column`, one per row (empty when not logged).
  const std::vector<double>& column(BenchColumn column) const { return columns[static_cast<int>(column)]; }
  /// The values of `column`, for the readers to fill.
  std::vector<double>& column(BenchColumn column) { return columns[static_cast<int>(column)]; }
};

}  // namespace propulsion_estimator

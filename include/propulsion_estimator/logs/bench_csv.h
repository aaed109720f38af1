#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/logs/csv_text.h"

namespace propulsion_estimator {

/// @file
/// The package's native bench CSV:
///   # key: value          metadata lines (esc, motor, propeller, supply, air_temperature_c,
///   #                     air_pressure_pa, experiment, ...), other '#' lines are comments
///   pwm_us,voltage_v,thrust_g,...   header of named columns, any order
///   1500,11.1,312.5,...             one row per sample
/// Required columns: pwm_us, voltage_v, and thrust_g or thrust_n. Optional: time_s, current_a,
/// power_w, rpm, ambient_temp_c, motor_temp_c, pressure_pa. Unknown columns are kept in
/// BenchLog::extra_columns.

/// The unit of a native log's thrust column: gram-force (thrust_g) or newton (thrust_n).
enum class ThrustUnit { kGram, kNewton };

/// Writes the logged columns of `log` (thrust as thrust_g or thrust_n), then its extra columns,
/// metadata first; parseNativeBenchCsv (or readBenchLog, for a file) reads it back (numbers to 6
/// significant digits).
void writeNativeBenchCsv(const BenchLog& log, std::ostream& out, ThrustUnit thrust_unit = ThrustUnit::kGram);
/// Writes the log to the file `path` as writeNativeBenchCsv does; InputError when it cannot be written.
void saveNativeBenchCsv(const BenchLog& log, const std::string& path, ThrustUnit thrust_unit = ThrustUnit::kGram);

/// Reads a native log from its text (files go through readBenchLog, which detects the format).
/// Throws DataError "<file>:<line>: column <n> '<name>': <problem>" for a cell that is empty,
/// text, NaN or infinite, and "<file>:<line>: ..." for a missing required column, a repeated
/// column, a repeated metadata key, an empty file or one without rows.
BenchLog parseNativeBenchCsv(const std::string& text, const std::string& source);
/// The same on an already split table (readBenchLog detects the format first).
BenchLog nativeBenchLogFromTable(const CsvText& table, DecimalSeparator decimal = DecimalSeparator::kAuto);

/// True when the header names one of pwm_us, voltage_v, thrust_g, thrust_n.
bool isNativeBenchHeader(const std::vector<std::string>& header);

}  // namespace propulsion_estimator

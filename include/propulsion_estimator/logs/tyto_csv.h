#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/logs/bench_read_options.h"
#include "propulsion_estimator/logs/csv_text.h"

namespace propulsion_estimator {

/// @file
/// The CSV that Tyto Robotics' RCbenchmark / Flight Stand software exports: one header of
/// "Name (unit)" columns, e.g. "ESC signal (µs)", "Thrust (kgf)" (or gf, N, lbf, ozf),
/// "Voltage (V)", "Current (A)", "Electrical Power (W)", "Motor Electrical Speed (RPM)",
/// "Motor Optical Speed (RPM)", plus dozens the package does not use (servo channels, torque,
/// vibration, "App message"), often with a byte-order mark and a trailing delimiter.

/// True when the header has an "ESC signal (µs)" (or "(us)") column.
bool isTytoHeader(const std::vector<std::string>& header);

/// Reads the table into SI columns. Thrust and current/power signs follow `options` (see
/// SignPolicy); of the two rpm columns the one with values is taken, and two with values are
/// refused unless options.columns names one. Unused columns go to BenchLog::extra_columns.
BenchLog tytoBenchLogFromTable(const CsvText& table, const BenchReadOptions& options);

}  // namespace propulsion_estimator

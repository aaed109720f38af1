#pragma once

#include <ostream>
#include <string>

#include "propulsion_estimator/core/bench_log.h"

namespace propulsion_estimator {

// The package's native bench CSV:
//   # key: value          metadata lines (esc, motor, propeller, supply, air_temperature_c,
//   #                     air_pressure_pa, experiment, ...), other '#' lines are comments
//   pwm_us,voltage_v,thrust_g,...   header of named columns, any order
//   1500,11.1,312.5,...             one row per sample
// Required columns: pwm_us, voltage_v, and thrust_g or thrust_n. Optional: time_s, current_a,
// power_w, rpm, ambient_temp_c, motor_temp_c, pressure_pa. Unknown columns are kept in
// BenchLog::extra_columns.

enum class ThrustUnit { kGram, kNewton };

// Writes the logged columns of `log` (thrust as thrust_g or thrust_n), metadata first.
void writeNativeBenchCsv(const BenchLog& log, std::ostream& out, ThrustUnit thrust_unit = ThrustUnit::kGram);
void saveNativeBenchCsv(const BenchLog& log, const std::string& path, ThrustUnit thrust_unit = ThrustUnit::kGram);

}  // namespace propulsion_estimator

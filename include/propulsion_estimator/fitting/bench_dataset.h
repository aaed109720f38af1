#pragma once

#include <array>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace fitting {

/// How rows are sorted into voltage and PWM levels. A log whose voltage stays near one value is
/// a sweep at one supply voltage (thesis 4.1) and forms one level, even where the supply sagged
/// at the top of the sweep; a log whose voltage wanders (a battery discharge, thesis 4.2 and 4.3)
/// has no levels of its own, and its rows are binned by voltage.
struct LevelOptions {
  /// A log is one level when the median absolute deviation of its voltage is at most this.
  double steady_voltage_mad_v = 0.15;
  /// Width of the voltage bins of the other logs' rows (thesis sweeps were 0.3 V apart).
  double voltage_bin_v = 0.3;
  /// Steady logs whose median voltages are closer than this are the same level (repeated runs).
  double same_level_v = 0.1;
  /// PWM levels are the distinct commanded values to 1 us; with more than this many, equal-width
  /// bins instead (a continuous ramp).
  int max_pwm_levels = 20;

  void validate() const;  ///< ConfigError for a non-positive value, naming its fit_surfaces option
};

/// A level: its centre and how many rows it holds.
struct Level {
  double centre = 0.0;  ///< the level's value: V for a voltage level, us for a PWM level
  int rows = 0;  ///< rows in the level
};

/// All rows of the logs of one fit, with outputs in the model's file units (thrust g, current A,
/// power W, efficiency g/W, rpm); NaN where a log did not measure an output.
struct BenchDataset {
  std::vector<std::string> sources;  ///< one per log
  std::vector<int> log;              ///< per row: index into sources
  std::vector<int> line;             ///< per row: line in its file
  std::vector<double> pwm_us;  ///< per row, the commanded pulse width, us
  std::vector<double> voltage_v;  ///< per row, the measured voltage, V
  std::array<std::vector<double>, kOutputCount> values;  ///< per row and Output, in the model's file units

  std::vector<int> voltage_level;  ///< per row, index into voltage_levels
  std::vector<Level> voltage_levels;  ///< voltage levels in rising order
  std::vector<int> pwm_level;  ///< per row, index into pwm_levels
  std::vector<Level> pwm_levels;  ///< PWM levels in rising order
  std::vector<std::string> notes;  ///< readers' notes and what building the dataset decided

  /// Number of rows.
  std::size_t rows() const { return pwm_us.size(); }
  /// The values of one output, per row.
  const std::vector<double>& output(Output o) const { return values[static_cast<int>(o)]; }
};

/// Only rows drawing at least this share of the log's peak power carry an efficiency sample:
/// near idle, thrust / power is a ratio of two noisy near-zero numbers.
constexpr double kEfficiencyMinPowerShare = 0.05;
/// A row this far below or above its steady log's median voltage is reported as supply sag.
constexpr double kSagNoteV = 0.5;

/// Joins the logs: converts units, takes power as voltage x current where a log has current but
/// no power (and says so), derives efficiency samples as thrust / power, and assigns levels.
/// Throws DataError "<file>:<line>: <column>: <value> is not a finite number" for a NaN or infinite
/// value, "<file>: ..." for a log without rows, without pwm_us, voltage_v or thrust_n, or with a
/// column whose length is not its number of rows; ConfigError for an empty list of logs.
BenchDataset buildBenchDataset(const std::vector<BenchLog>& logs, const LevelOptions& options);

}  // namespace fitting
}  // namespace propulsion_estimator

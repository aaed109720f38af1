#include "propulsion_estimator/gap/bench_gap.h"

#include <algorithm>

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {
namespace gap {

BenchGap benchGap(const ThrustViews& views, const BenchLog& log) {
  BenchGap gap;
  gap.source = log.source;
  const std::vector<double>& pwm = log.column(BenchColumn::kPwm);
  const std::vector<double>& voltage = log.column(BenchColumn::kVoltage);
  const std::vector<double>& thrust = log.column(BenchColumn::kThrust);
  const double max_thrust = thrust.empty() ? 0.0 : *std::max_element(thrust.begin(), thrust.end());
  // Rows as blocks: the truth is the load cell, the "view" the model at the logged inputs.
  std::vector<Block> rows;
  for (std::size_t i = 0; i < log.rows(); ++i) {
    if (!(thrust[i] > 0.05 * max_thrust)) continue;
    Block row;
    row.pwm_us[0] = pwm[i];
    row.voltage_v = voltage[i];
    row.truth_n = thrust[i];
    row.signals.set(effects::Signal::kMotorTemperature,
                    log.has(BenchColumn::kMotorTemp) ? log.column(BenchColumn::kMotorTemp)[i] : kNaN);
    rows.push_back(row);
  }
  std::vector<const Block*> all;
  for (const Block& row : rows) all.push_back(&row);
  const auto view = [&](const Block& row) { return views.surfaceThrust(row.pwm_us[0], row.voltage_v); };
  gap.stats = statsOf(all, view);
  gap.where.push_back(breakdownBy("voltage_v", all, [](const Block& row) { return row.voltage_v; },
                                  quantileEdges(all, [](const Block& row) { return row.voltage_v; }, 4), view, "%.2f",
                                  "a voltage column"));
  const effects::Signal signal = effects::Signal::kMotorTemperature;
  const auto temperature = [signal](const Block& row) { return row.signals.value(signal); };
  gap.where.push_back(breakdownBy(effects::signalKey(signal), all, temperature, quantileEdges(all, temperature, 4), view,
                                  "%.1f", "a motor_temp_c column"));
  return gap;
}

}  // namespace gap
}  // namespace propulsion_estimator

#include "propulsion_estimator/logs/bench_log.h"

namespace propulsion_estimator {

const char* benchColumnName(BenchColumn column) {
  static const char* const kNames[kBenchColumnCount] = {"time_s",  "pwm_us", "voltage_v",      "thrust_n",
                                                        "current_a", "power_w", "rpm", "ambient_temp_c",
                                                        "motor_temp_c", "pressure_pa"};
  return kNames[static_cast<int>(column)];
}

}  // namespace propulsion_estimator

#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "propulsion_estimator/sim/flight/flight_sensors.h"
#include "propulsion_estimator/sim/flight/flight_sink.h"
#include "propulsion_estimator/sim/physics/power_train.h"

namespace propulsion_estimator {
namespace sim {

/// The ESCs' telemetry of a simulated flight: each ESC's rotor speed, input current and voltage as
/// its own sensors report them (FlightSensorParams' esc_* figures), drawn from a random stream of
/// its own so that the flight's other streams are those of a flight without telemetry.
class EscTelemetrySensor {
 public:
  /// `motors` ESCs; their current and voltage gain errors are drawn here from `seed`.
  EscTelemetrySensor(const FlightSensorParams& sensors, int motors, bool px4, std::uint64_t seed);

  /// The packet the autopilot forwards at `time_s` for the power train's state `power`: each ESC's
  /// new reading, or its previous one where the packet was lost.
  const EscTelemetrySample& read(double time_s, const PowerTrainState& power);

 private:
  double noise(double sigma);
  bool lost();

  const FlightSensorParams& sensors_;
  std::mt19937_64 rng_;
  std::vector<double> current_gain_, current_offset_a_, voltage_gain_;
  EscTelemetrySample sample_;
};

}  // namespace sim
}  // namespace propulsion_estimator

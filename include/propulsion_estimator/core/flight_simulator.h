#pragma once

#include <cstdint>
#include <vector>

#include "propulsion_estimator/core/flight_manifest.h"
#include "propulsion_estimator/core/flight_profile.h"
#include "propulsion_estimator/core/flight_sensors.h"
#include "propulsion_estimator/core/flight_sink.h"
#include "propulsion_estimator/core/sim_effects.h"
#include "propulsion_estimator/core/sim_params.h"
#include "propulsion_estimator/core/vehicle.h"

namespace propulsion_estimator {

// Physics step of the flight simulation; the controller runs at the same rate (PX4's rate loop
// runs at 250 Hz-1 kHz).
constexpr double kFlightStepS = 0.002;

struct FlightResult {
  // One segment per hover longer than the profile's settle time: from settle time after its start
  // to its end, with the vehicle's mass plus the hanging payload's. Times from the first message.
  std::vector<ManifestSegment> segments;
  double duration_s = 0.0;
  double final_state_of_charge = 0.0;
};

// Flies `profile` with the vehicle `vehicle` (rotors in motor order with positions, and empty mass
// properties), every rotor driven by the chain of `params` and all fed by its battery, in the
// bench's air unless the air_density effect sets another. Emits every reading to `sink` at its
// rate, all streams starting at t = 0. The same inputs and seed give the same flight. Throws
// ConfigError "<profile>: segments[i].mass_kg: ..." when a payload makes the vehicle too heavy to
// hover on less than 80 % of its maximum thrust, and "<profile>: ... the battery is empty ..."
// when the flight outlasts it.
FlightResult simulateFlight(const SimParams& params, const SimEffects& effects, const FlightProfile& profile,
                            const Vehicle& vehicle, std::uint64_t seed, FlightSink* sink,
                            const FlightSensorParams& sensors = {});

}  // namespace propulsion_estimator

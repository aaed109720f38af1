#pragma once

#include <cstdint>
#include <vector>

#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/sim/flight/flight_profile.h"
#include "propulsion_estimator/sim/flight/flight_sensors.h"
#include "propulsion_estimator/sim/flight/flight_sink.h"
#include "propulsion_estimator/sim/physics/sim_effects.h"
#include "propulsion_estimator/sim/physics/sim_params.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace sim {

/// Physics step of the flight simulation; the controller runs at the same rate (PX4's rate loop
/// runs at 250 Hz-1 kHz).
constexpr double kFlightStepS = 0.002;

/// What simulateFlight returns besides the messages it emits: the manifest's segments, the flight's
/// duration in s and the battery's final state of charge (0..1).
struct FlightResult {
  /// One segment per span of the profile's manifest (manifestSpans: its hovers, or its stretches in
  /// the air), with the vehicle's mass plus the hanging payload's; a span in which a foot or the
  /// payload touched the ground is cut there and resumes the settle time after the touch. Times
  /// from the first message.
  std::vector<ManifestSegment> segments;
  double duration_s = 0.0;  ///< s, from the first message to the last
  double final_state_of_charge = 0.0;  ///< 0..1 at the end of the flight
};

/// The refusals simulateFlight makes before it flies, without flying (cheap: for callers that
/// open an output only for a flight that can start): FieldError or ConfigError for invalid
/// parameters, effects, sensors or profile; "<urdf>: ..." for a vehicle the simulator cannot fly
/// (no mass properties, a rotor layout the mixer cannot control); "<profile>: segments[i].mass_kg:
/// ..." when a payload makes the vehicle too heavy to hover on less than 80 % of its maximum thrust
/// (with intact propellers of the parameter file's chain), "<profile>: faults.weak_propeller.motor:
/// ..." for a motor the vehicle does not have, and "<profile>: vehicle.parts: motor k's drawn
/// propeller.torque_coefficient: ..." for a motor whose drawn parts make a chain the simulator
/// refuses; FieldError "esc_offset.per_esc_us" for an effects file's ESC offsets of another count
/// than the vehicle's rotors.
void checkFlight(const SimParams& params, const SimEffects& effects, const FlightProfile& profile,
                 const Vehicle& vehicle, const FlightSensorParams& sensors = {});

/// Flies `profile` with the vehicle `vehicle` (rotors in motor order with positions, and empty mass
/// properties), every rotor driven by the chain of `params` (with the vehicle's own parts when the
/// profile draws them, drawMotorParts; then the profile's weak propeller, if any, scaled down:
/// scaledPropeller or wornPropeller) and all fed by its battery, in the bench's air unless the
/// air_density effect sets another. Emits every reading to `sink` at its
/// rate, all streams starting at t = 0. The same inputs and seed give the same flight. Before it
/// flies it refuses what checkFlight refuses. While flying it throws SimulationError
/// "<profile>: segments[i].type: the vehicle ended its hover at ..." or "... had not landed and
/// disarmed ..." for a segment that did not end as scripted, "<profile>: segments[i].type: the
/// vehicle flipped over: roll R deg, pitch P deg at t = X s, beyond 60 deg since Y s" when roll or
/// pitch stays beyond 60 deg for 0.3 s (PX4's failure detector; on the ground too: upside down
/// and still is not landed), "<profile>: vehicle.battery_initial_soc:
/// the battery is empty ..." when the flight outlasts the battery, and "<profile>: the simulation
/// diverged at t = X s" when the state stops being finite.
FlightResult simulateFlight(const SimParams& params, const SimEffects& effects, const FlightProfile& profile,
                            const Vehicle& vehicle, std::uint64_t seed, FlightSink* sink,
                            const FlightSensorParams& sensors = {});

}  // namespace sim
}  // namespace propulsion_estimator

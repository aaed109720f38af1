#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "propulsion_estimator/sim/flight/airframe.h"

namespace propulsion_estimator {
namespace sim {

/// What a segment of the flight script does (the profile's `type`).
enum class SegmentKind { kWait, kTakeoff, kHover, kClimb, kDescend, kLand, kPayload, kMove };
/// "wait", "takeoff", ...: as the profile spells the segment's type.
const char* segmentKindName(SegmentKind kind);

/// One step of the flight script. Heights are of base_link above the ground.
struct FlightSegment {
  SegmentKind kind = SegmentKind::kWait;  ///< what the segment does
  double duration_s = 0.0;       ///< wait, hover, payload
  double height_m = 0.0;         ///< takeoff, climb, descend: target height
  double rate_m_s = 0.0;         ///< takeoff, climb, descend, land: vertical speed
  double payload_mass_kg = 0.0;  ///< payload: the new payload, 0.01..5 kg (0 = none)
  Eigen::Vector2d displacement_m = Eigen::Vector2d::Zero();  ///< move: east, north, m (ENU)
  double speed_m_s = 0.0;        ///< move: horizontal speed, m/s
};

/// What the manifest of a flight holds (see manifestSpans): its hovers, or every stretch in the
/// air between a take-off and a landing.
enum class ManifestSpans { kHovers, kAirborne };

/// A simulated flight: the autopilot, the vehicle, the payload cable, faults, the manifest's spans
/// and the script of segments (config/sim/*_flight.yaml).
struct FlightProfile {
  std::string source;  ///< file it came from, for messages
  AutopilotParams autopilot;  ///< flavour, PWM end points, rc/out rate
  VehicleSetup vehicle;  ///< URDF, centre-of-mass offset, landing gear, drag, battery
  PayloadCable cable;  ///< how the payload hangs
  VehicleFaults faults;  ///< what is wrong with the vehicle, for validation
  double manifest_settle_s = 0.0;  ///< a span enters the manifest this long after it starts
  ManifestSpans manifest_spans = ManifestSpans::kHovers;  ///< what the manifest's spans are
  std::vector<FlightSegment> segments;  ///< the script, in order

  /// Throws FieldError naming the key ("segments[3].height_m", "autopilot.pwm_max_us") for values
  /// out of range and for segments impossible where they stand: taking off or changing the payload
  /// while flying, hovering, climbing, descending or landing while on the ground, climbing to a
  /// lower or descending to a higher height, hovering so low that the payload would rest on the
  /// ground (with airborne manifest spans: taking off, climbing or descending so low), and a
  /// profile that does not end on the ground. A weak propeller's motor is checked against the
  /// vehicle by checkFlight.
  void validate() const;
};

/// A segment placed in time, with the height setpoint at its ends.
struct ScheduledSegment {
  FlightSegment segment;  ///< as scripted
  int index = 0;  ///< in FlightProfile::segments
  double start_s = 0.0;  ///< s from the flight's start
  double end_s = 0.0;  ///< s from the flight's start
  double start_height_m = 0.0;  ///< m, the height setpoint at the start
  double end_height_m = 0.0;  ///< m, the height setpoint at the end
  double payload_mass_kg = 0.0;  ///< attached during the segment
  Eigen::Vector2d start_position_m = Eigen::Vector2d::Zero();  ///< east, north setpoint at the start, m
};

/// Spin-up on the ground before a take-off climbs, and time a landing gets after touching down to
/// detect it and disarm.
constexpr double kTakeoffSpinUpS = 2.0;
constexpr double kTouchdownS = 4.0;  ///< s a landing gets after its descent to touch down and disarm

/// The profile's segments in time, starting at 0 on the ground at the origin: climbs last height /
/// rate (plus the spin-up for a take-off), moves distance / speed, landings their descent plus
/// kTouchdownS. Validates first
/// (FieldError, see FlightProfile::validate).
std::vector<ScheduledSegment> scheduleFlight(const FlightProfile& profile);

/// A stretch of a flight in which the vehicle carries a known payload, for the manifest.
struct ManifestSpan {
  double start_s = 0.0;  ///< s from the flight's start
  double end_s = 0.0;  ///< s from the flight's start
  double payload_mass_kg = 0.0;  ///< kg carried during the span
};

/// The spans of the profile's manifest, in time order, from its schedule:
///   kHovers    every hover from manifest_settle_s after it starts to its end;
///   kAirborne  every stretch from a take-off to the next landing (its payload cannot change in
///              between): from manifest_settle_s after the lowest point left the ground (the
///              feet, or the payload hanging on its cable once it is taut) to the moment the
///              landing brings that point within 0.2 m of the ground, as scripted.
/// A span the settle time leaves empty is left out. The flight simulator also leaves out any time
/// a foot or the payload actually touched the ground within a span, and the settle time after it.
std::vector<ManifestSpan> manifestSpans(const FlightProfile& profile, const std::vector<ScheduledSegment>& schedule);

}  // namespace sim
}  // namespace propulsion_estimator

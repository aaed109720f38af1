#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/sim/flight/airframe.h"

namespace propulsion_estimator {

enum class SegmentKind { kWait, kTakeoff, kHover, kClimb, kDescend, kLand, kPayload };
const char* segmentKindName(SegmentKind kind);  // "wait", "takeoff", ...

// One step of the flight script. Heights are of base_link above the ground.
struct FlightSegment {
  SegmentKind kind = SegmentKind::kWait;
  double duration_s = 0.0;       // wait, hover, payload
  double height_m = 0.0;         // takeoff, climb, descend: target height
  double rate_m_s = 0.0;         // takeoff, climb, descend, land: vertical speed
  double payload_mass_kg = 0.0;  // payload: the new payload, 0.01..5 kg (0 = none)
};

struct FlightProfile {
  std::string source;  // file it came from, for messages
  AutopilotParams autopilot;
  VehicleSetup vehicle;
  PayloadCable cable;
  double manifest_settle_s = 0.0;  // a hover enters the manifest this long after it starts
  std::vector<FlightSegment> segments;

  // Throws FieldError naming the key ("segments[3].height_m", "autopilot.pwm_max_us") for values
  // out of range and for segments impossible where they stand: taking off or changing the payload
  // while flying, hovering, climbing, descending or landing while on the ground, climbing to a
  // lower or descending to a higher height, hovering so low that the payload would rest on the
  // ground, and a profile that does not end on the ground.
  void validate() const;
};

// A segment placed in time, with the height setpoint at its ends.
struct ScheduledSegment {
  FlightSegment segment;
  int index = 0;  // in FlightProfile::segments
  double start_s = 0.0;
  double end_s = 0.0;
  double start_height_m = 0.0;
  double end_height_m = 0.0;
  double payload_mass_kg = 0.0;  // attached during the segment
};

// Spin-up on the ground before a take-off climbs, and time a landing gets after touching down to
// detect it and disarm.
constexpr double kTakeoffSpinUpS = 2.0;
constexpr double kTouchdownS = 4.0;

// The profile's segments in time, starting at 0 on the ground: climbs last height / rate (plus
// the spin-up for a take-off), landings their descent plus kTouchdownS. Validates first.
std::vector<ScheduledSegment> scheduleFlight(const FlightProfile& profile);

}  // namespace propulsion_estimator

#include "propulsion_estimator/sim/flight/flight_profile.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// The lowest height a climb, descent or take-off may aim at, above the landed height.
constexpr double kMinimumClearanceM = 0.05;
// How high a hanging payload must stay above the ground while hovering.
constexpr double kPayloadClearanceM = 0.2;
constexpr double kMaxHeightM = 100.0;
// Climbs, descents and landings last height / rate: slower than this they are hovers (and a rate
// near 0 would schedule a flight of years).
constexpr double kSlowestRateM_S = 0.05;
// A lighter payload is far below what the estimator can weigh; one below ~0.1 g would also let
// its drag (a 10 cm box) outrun the explicit 2 ms step of its motion.
constexpr double kLightestPayloadKg = 0.01;

std::string metres(double value) { return formatNumber(value) + " m"; }

// Height of base_link at which the lowest point of the vehicle touches the ground: its feet, or
// the payload hanging on the taut cable below the attachment point.
double touchdownHeight(const FlightProfile& profile, double payload_kg) {
  return payload_kg > 0.0 ? profile.cable.length_m - profile.cable.attach_point_m.z()
                          : profile.vehicle.landing_gear_height_m;
}

}  // namespace

const char* segmentKindName(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::kWait: return "wait";
    case SegmentKind::kTakeoff: return "takeoff";
    case SegmentKind::kHover: return "hover";
    case SegmentKind::kClimb: return "climb";
    case SegmentKind::kDescend: return "descend";
    case SegmentKind::kLand: return "land";
    case SegmentKind::kPayload: return "payload";
    case SegmentKind::kMove: return "move";
  }
  return "?";
}

void FlightProfile::validate() const {
  requireWithin("autopilot.pwm_min_us", autopilot.pwm_min_us, 800.0, 2000.0, " us");
  requireWithin("autopilot.pwm_max_us", autopilot.pwm_max_us, autopilot.pwm_min_us + 200.0, 2200.0, " us");
  if (autopilot.disarmed_pwm_us != 0.0) {
    requireWithin("autopilot.disarmed_pwm_us", autopilot.disarmed_pwm_us, 500.0, autopilot.pwm_min_us, " us (or 0)");
  }
  // At most every physics step (kFlightStepS, 500 Hz): PX4 logs actuator outputs at up to 400 Hz.
  requireWithin("autopilot.rc_out_rate_hz", autopilot.rc_out_rate_hz, 10.0, 500.0, " Hz");
  if (vehicle.urdf_path.empty()) throw FieldError("vehicle.urdf", "is empty");
  if (!vehicle.centre_of_mass_offset_m.allFinite() || vehicle.centre_of_mass_offset_m.norm() > 0.1) {
    throw FieldError("vehicle.centre_of_mass_offset_m", "must be a finite offset within 0.1 m");
  }
  requirePositive("vehicle.landing_gear.height_m", vehicle.landing_gear_height_m, 1.0, " m");
  requirePositive("vehicle.landing_gear.half_width_m", vehicle.landing_gear_half_width_m, 1.0, " m");
  requireWithin("vehicle.drag_area_m2", vehicle.drag_area_m2, 0.0, 1.0, " m^2");
  requirePositive("vehicle.battery_initial_soc", vehicle.battery_initial_soc, 1.0, "");
  requireWithin("vehicle.avionics_current_a", vehicle.avionics_current_a, 0.0, 5.0, " A");
  if (vehicle.parts) vehicle.parts->validate();
  requireWithin("payload_cable.length_m", cable.length_m, 0.1, 10.0, " m");
  if (!cable.attach_point_m.allFinite() || cable.attach_point_m.norm() > 1.0) {
    throw FieldError("payload_cable.attach_point_m", "must be a finite point within 1 m of base_link");
  }
  requirePositive("payload_cable.stiffness_n_per_m", cable.stiffness_n_per_m, 1e5, " N/m");
  requireWithin("payload_cable.damping_n_s_per_m", cable.damping_n_s_per_m, 0.0, 1e3, " N s/m");
  if (faults.weak_propeller) {
    if (faults.weak_propeller->motor < 1) {
      throw FieldError("faults.weak_propeller.motor",
                       std::to_string(faults.weak_propeller->motor) + " is not a motor (they count from 1)");
    }
    // Down to a propeller that lost most of a blade; 1 is an intact one.
    requireWithin("faults.weak_propeller.thrust_factor", faults.weak_propeller->thrust_factor, 0.1, 1.0, "");
  }
  requireWithin("manifest.settle_s", manifest_settle_s, 0.0, 60.0, " s");
  const bool airborne_spans = manifest_spans == ManifestSpans::kAirborne;
  if (segments.empty()) throw FieldError("segments", "no segments");

  const double landed = vehicle.landing_gear_height_m;
  // Rounded to the micrometre so that messages quote "0.17", not "0.16999999999999998".
  const double lowest = std::round((landed + kMinimumClearanceM) * 1e6) / 1e6;
  bool flying = false;
  double height = landed;
  double payload = 0.0;
  // How high base_link must stay for a hanging payload to clear the ground.
  const double needed = std::round((cable.length_m - cable.attach_point_m.z() + kPayloadClearanceM) * 1e6) / 1e6;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const FlightSegment& s = segments[i];
    const std::string at = "segments[" + std::to_string(i) + "].";
    const std::string kind = segmentKindName(s.kind);
    const bool needs_ground =
        s.kind == SegmentKind::kWait || s.kind == SegmentKind::kPayload || s.kind == SegmentKind::kTakeoff;
    if (needs_ground && flying)
      throw FieldError(at + "type", kind + " while flying at " + metres(height) + " (land first)");
    if (!needs_ground && !flying) throw FieldError(at + "type", kind + " on the ground (take off first)");
    switch (s.kind) {
      case SegmentKind::kWait:
      case SegmentKind::kHover: requirePositive(at + "duration_s", s.duration_s, 3600.0, " s"); break;
      case SegmentKind::kPayload:
        requirePositive(at + "duration_s", s.duration_s, 3600.0, " s");
        if (s.payload_mass_kg != 0.0) {
          requireWithin(at + "mass_kg", s.payload_mass_kg, kLightestPayloadKg, 5.0, " kg (or 0 for none)");
        }
        payload = s.payload_mass_kg;
        break;
      case SegmentKind::kTakeoff:
      case SegmentKind::kClimb:
      case SegmentKind::kDescend:
        requireWithin(at + "rate_m_s", s.rate_m_s, kSlowestRateM_S, 5.0, " m/s");
        requireWithin(at + "height_m", s.height_m, lowest, kMaxHeightM, " m");
        if (s.kind == SegmentKind::kClimb && !(s.height_m > height)) {
          throw FieldError(at + "height_m",
                           "climb to " + metres(s.height_m) + " from " + metres(height) + " (use descend)");
        }
        if (s.kind == SegmentKind::kDescend && !(s.height_m < height)) {
          throw FieldError(at + "height_m",
                           "descend to " + metres(s.height_m) + " from " + metres(height) + " (use climb)");
        }
        if (airborne_spans && payload > 0.0 && s.height_m < needed) {
          throw FieldError(at + "height_m", kind + " to " + metres(s.height_m) + " with the " + formatNumber(payload) +
                                                " kg payload on a " + metres(cable.length_m) +
                                                " cable: the payload would rest on the ground within an airborne "
                                                "manifest span (stay at " +
                                                metres(needed) + " or higher)");
        }
        height = s.height_m;
        flying = true;
        break;
      case SegmentKind::kLand:
        requireWithin(at + "rate_m_s", s.rate_m_s, kSlowestRateM_S, 5.0, " m/s");
        height = landed;
        flying = false;
        break;
      case SegmentKind::kMove:
        // Up to a fast multicopter's cruise; the controller tilts at most 20 deg to hold it.
        requireWithin(at + "speed_m_s", s.speed_m_s, 0.2, 12.0, " m/s");
        if (!s.displacement_m.allFinite() || !(s.displacement_m.norm() >= 0.1) || s.displacement_m.norm() > 2000.0) {
          throw FieldError(at + "east_m", "a move of " + metres(s.displacement_m.norm()) + " (0.1 to 2000 m)");
        }
        break;
    }
    if (s.kind == SegmentKind::kHover && payload > 0.0 && height < needed) {
      throw FieldError(at + "type", "hover at " + metres(height) + " with the " + formatNumber(payload) +
                                        " kg payload on a " + metres(cable.length_m) +
                                        " cable: the payload would rest on the ground (hover at " + metres(needed) +
                                        " or higher)");
    }
  }
  if (flying) throw FieldError("segments", "the profile ends in flight (add a land segment)");
}

std::vector<ScheduledSegment> scheduleFlight(const FlightProfile& profile) {
  profile.validate();
  std::vector<ScheduledSegment> schedule;
  double time = 0.0;
  double height = profile.vehicle.landing_gear_height_m;
  double payload = 0.0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < profile.segments.size(); ++i) {
    const FlightSegment& s = profile.segments[i];
    ScheduledSegment scheduled{s, static_cast<int>(i), time, time, height, height, payload, position};
    double duration = s.duration_s;
    switch (s.kind) {
      case SegmentKind::kPayload:
        payload = s.payload_mass_kg;
        scheduled.payload_mass_kg = payload;
        break;
      case SegmentKind::kTakeoff:
      case SegmentKind::kClimb:
      case SegmentKind::kDescend:
        duration =
            std::fabs(s.height_m - height) / s.rate_m_s + (s.kind == SegmentKind::kTakeoff ? kTakeoffSpinUpS : 0.0);
        height = s.height_m;
        break;
      case SegmentKind::kLand:
        duration = (height - profile.vehicle.landing_gear_height_m) / s.rate_m_s + kTouchdownS;
        height = profile.vehicle.landing_gear_height_m;
        break;
      case SegmentKind::kMove:
        duration = s.displacement_m.norm() / s.speed_m_s;
        position += s.displacement_m;
        break;
      case SegmentKind::kWait:
      case SegmentKind::kHover: break;
    }
    scheduled.end_s = time + duration;
    scheduled.end_height_m = height;
    schedule.push_back(scheduled);
    time = scheduled.end_s;
  }
  return schedule;
}

std::vector<ManifestSpan> manifestSpans(const FlightProfile& profile, const std::vector<ScheduledSegment>& schedule) {
  std::vector<ManifestSpan> spans;
  const auto add = [&](double start_s, double end_s, double payload_kg) {
    if (start_s + profile.manifest_settle_s < end_s) spans.push_back({start_s + profile.manifest_settle_s, end_s, payload_kg});
  };
  for (std::size_t i = 0; i < schedule.size(); ++i) {
    const ScheduledSegment& takeoff = schedule[i];
    if (profile.manifest_spans == ManifestSpans::kHovers) {
      if (takeoff.segment.kind == SegmentKind::kHover) add(takeoff.start_s, takeoff.end_s, takeoff.payload_mass_kg);
      continue;
    }
    if (takeoff.segment.kind != SegmentKind::kTakeoff) continue;
    std::size_t j = i + 1;
    while (schedule[j].segment.kind != SegmentKind::kLand) ++j;  // validated: every flight lands
    const ScheduledSegment& land = schedule[j];
    const double touchdown = touchdownHeight(profile, takeoff.payload_mass_kg);
    const double lift_off = takeoff.start_s + kTakeoffSpinUpS +
                            (touchdown - takeoff.start_height_m) / takeoff.segment.rate_m_s;
    const double stop = land.start_s + std::max(0.0, land.start_height_m - (touchdown + kPayloadClearanceM)) /
                                           land.segment.rate_m_s;
    add(lift_off, stop, takeoff.payload_mass_kg);
  }
  return spans;
}

}  // namespace sim
}  // namespace propulsion_estimator

#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace propulsion_estimator {

// Autopilots differ in what MAVROS shows of them: PX4 outputs PWM_MAIN_DISARM (900 us) on a
// disarmed ESC and its battery current arrives negated on /mavros/battery; ArduPilot outputs
// MOT_PWM_MIN (1000 us), or nothing (0) with MOT_SAFE_DISARM, and a positive current.
enum class AutopilotFlavour { kPx4, kArduPilot };

struct AutopilotParams {
  AutopilotFlavour flavour = AutopilotFlavour::kPx4;
  double pwm_min_us = 0.0;       // mixer output 0 while armed (PX4 PWM_MAIN_MIN, ArduPilot MOT_PWM_MIN/SPIN_ARM)
  double pwm_max_us = 0.0;       // mixer output 1
  double disarmed_pwm_us = 0.0;  // what the ESCs get while disarmed
  double rc_out_rate_hz = 0.0;   // /mavros/rc/out (and /sim/truth) publication rate
};

struct VehicleSetup {
  std::string urdf_path;                                              // resolved against the profile's folder
  Eigen::Vector3d centre_of_mass_offset_m = Eigen::Vector3d::Zero();  // added to the URDF's centre of mass
  double landing_gear_height_m = 0.0;                                 // base_link above the ground when landed
  double landing_gear_half_width_m = 0.0;                             // feet at (+-w, +-w) under base_link
  double drag_area_m2 = 0.0;                                          // Cd A of the airframe
  double battery_initial_soc = 1.0;
};

// A payload hangs on a cable from a point of the airframe; it is attached and changed while landed.
struct PayloadCable {
  double length_m = 0.0;
  Eigen::Vector3d attach_point_m = Eigen::Vector3d::Zero();  // in base_link
  double stiffness_n_per_m = 0.0;                            // along the cable, which only pulls
  double damping_n_s_per_m = 0.0;
};

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

// The simulated vehicle stays upright, landings included, on hardware drawn at the edges of the
// validation's randomized family (scripts/validate_gap.py draw_family): rotors that spin up slowly,
// weak motors near full throttle, strong fast ones; with the centre of gravity off by 12 mm, short
// landing gear, and the heaviest payload on its cable down to the ground. With the flight
// controller's old rate integral (its zero at 5 rad/s) the slow rotors rang at 1-2 Hz and flipped
// over; without the mixer's desaturation the weak motors, clipped at full output, tilted 53 deg.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "recording_flight_sink.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
using pe::sim::FlightSegment;
using pe::sim::SegmentKind;

namespace {

// The family's extremes, as factors on the thesis hardware (draw_family's ranges).
struct Draw {
  const char* name;
  double kv, winding, esc_ohm, thrust_coefficient, torque_coefficient;
};
const Draw kSlowSpinUp{"rotors slow to spin up", 1.0, 1.35, 0.04, 1.0, 1.10};
const Draw kWeak{"weak motors near full throttle", 0.94, 1.35, 0.04, 0.93, 1.10};
const Draw kStrong{"fast rotors, much thrust per command", 1.06, 0.75, 0.01, 1.07, 0.90};

pe::sim::SimParams drawnParams(const Draw& draw) {
  pe::sim::SimParams params = pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
  params.chain.motor.kv_rpm_per_v *= draw.kv;
  params.chain.motor.winding_resistance_ohm *= draw.winding;
  params.chain.esc.resistance_ohm = draw.esc_ohm;
  params.chain.propeller.thrust_coefficient *= draw.thrust_coefficient;
  params.chain.propeller.torque_coefficient *= draw.torque_coefficient;
  return params;
}

FlightSegment segment(SegmentKind kind, double duration_s, double height_m = 0.0, double rate_m_s = 0.0,
                      double payload_kg = 0.0) {
  FlightSegment s;
  s.kind = kind;
  s.duration_s = duration_s;
  s.height_m = height_m;
  s.rate_m_s = rate_m_s;
  s.payload_mass_kg = payload_kg;
  return s;
}

// Two lifts as validate_gap flies them: with the family's heaviest payload on a short cable, down
// to 0.45 m and landed; then empty, down to 0.2 m and landed. Short gear, centre of gravity 12 mm
// off diagonally, a battery part-charged.
pe::sim::FlightProfile landingProfile() {
  pe::sim::FlightProfile profile = pe::sim::loadFlightProfileFile(repoPath("config/sim/default_flight.yaml"));
  profile.vehicle.centre_of_mass_offset_m = Eigen::Vector3d(0.0085, -0.0085, 0.0);
  profile.vehicle.landing_gear_height_m = 0.10;
  profile.vehicle.battery_initial_soc = 0.8;
  profile.cable.length_m = 0.15;
  profile.manifest_settle_s = 4.0;
  profile.manifest_spans = pe::sim::ManifestSpans::kAirborne;
  profile.segments = {segment(SegmentKind::kWait, 3.0),
                      segment(SegmentKind::kPayload, 3.0, 0.0, 0.0, 0.22),
                      segment(SegmentKind::kTakeoff, 0.0, 2.0, 1.0),
                      segment(SegmentKind::kHover, 10.0),
                      segment(SegmentKind::kDescend, 0.0, 0.45, 1.5),
                      segment(SegmentKind::kHover, 10.0),
                      segment(SegmentKind::kLand, 0.0, 0.0, 0.6),
                      segment(SegmentKind::kPayload, 3.0),
                      segment(SegmentKind::kTakeoff, 0.0, 2.0, 1.0),
                      segment(SegmentKind::kHover, 10.0),
                      segment(SegmentKind::kDescend, 0.0, 0.2, 1.5),
                      segment(SegmentKind::kHover, 10.0),
                      segment(SegmentKind::kLand, 0.0, 0.0, 0.6),
                      segment(SegmentKind::kWait, 2.0)};
  return profile;
}

// The largest tilt of the body's z axis from the vertical over the flight, degrees.
double largestTiltDeg(const RecordingFlightSink& sink) {
  double lowest_cosine = 1.0;
  for (const pe::sim::PoseSample& pose : sink.poses) {
    lowest_cosine = std::min(lowest_cosine, pose.orientation.toRotationMatrix()(2, 2));
  }
  return std::acos(std::clamp(lowest_cosine, -1.0, 1.0)) * 180.0 / M_PI;
}

void expectUprightLandings(const Draw& draw) {
  const pe::sim::FlightProfile profile = landingProfile();
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  // The controller is given the true state: the sensors' noise, the only thing a seed draws,
  // does not move the vehicle.
  RecordingFlightSink sink;
  pe::sim::FlightResult result;
  ASSERT_NO_THROW(result = pe::sim::simulateFlight(drawnParams(draw), {}, profile, vehicle, 1, &sink)) << draw.name;
  // Both landings disarmed (the simulator refuses a landing that did not), and the attitude never
  // left what a hover with a swinging payload asks: the controller tilts at most 20 deg.
  EXPECT_LT(largestTiltDeg(sink), 25.0) << draw.name;
  // Both lifts weighed (a descent's overshoot onto the ground may cut a lift's span in two).
  const auto carried = [&](double mass_kg) {
    return std::count_if(result.segments.begin(), result.segments.end(),
                         [&](const pe::ManifestSegment& s) { return std::fabs(s.mass_kg - mass_kg) < 1e-6; });
  };
  EXPECT_GE(carried(1.315 + 0.22), 1) << draw.name;
  EXPECT_GE(carried(1.315), 1) << draw.name;
}

}  // namespace

TEST(FlightLanding, RotorsSlowToSpinUpLandUpright) { expectUprightLandings(kSlowSpinUp); }

TEST(FlightLanding, WeakMotorsNearFullThrottleLandUpright) { expectUprightLandings(kWeak); }

TEST(FlightLanding, StrongRotorsLandUpright) { expectUprightLandings(kStrong); }

// Simulated flights of the thesis quad: the controller holds the script, the truth balances the
// weight, the payload hangs, the streams keep their rates, and impossible flights are refused.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/simulation_error.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "recording_flight_sink.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

pe::sim::FlightProfile defaultProfile() {
  return pe::sim::loadFlightProfileFile(repoPath("config/sim/default_flight.yaml"));
}

struct Flight {
  RecordingFlightSink sink;
  pe::sim::FlightResult result;
  std::vector<pe::sim::ScheduledSegment> schedule;
};

Flight fly(const pe::sim::FlightProfile& profile, std::uint64_t seed = 1) {
  Flight flight;
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  flight.result = pe::sim::simulateFlight(thesisParams(), {}, profile, vehicle, seed, &flight.sink);
  flight.schedule = pe::sim::scheduleFlight(profile);
  return flight;
}

const Flight& defaultFlight() {
  static const Flight flight = fly(defaultProfile());
  return flight;
}

template <typename Sample, typename F>
void forSegment(const std::vector<Sample>& samples, const pe::ManifestSegment& segment, F f) {
  for (const Sample& sample : samples) {
    if (sample.time_s >= segment.start_s && sample.time_s <= segment.end_s) f(sample);
  }
}

// The refusal's message; a refusal of another class than Error escapes.
template <typename Error = pe::InputError>
std::string refusal(const pe::sim::FlightProfile& profile) {
  try {
    fly(profile);
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(FlightSimulator, ManifestSegmentsAreTheHoversWithTheirTrueMasses) {
  const Flight& flight = defaultFlight();
  const double settle = defaultProfile().manifest_settle_s;
  std::vector<pe::ManifestSegment> expected;
  for (const pe::sim::ScheduledSegment& s : flight.schedule) {
    if (s.segment.kind == pe::sim::SegmentKind::kHover)
      expected.push_back({s.start_s + settle, s.end_s, 1.315 + s.payload_mass_kg});
  }
  ASSERT_EQ(flight.result.segments.size(), 4u);
  ASSERT_EQ(expected.size(), 4u);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(flight.result.segments[i].start_s, expected[i].start_s, 1e-6);
    EXPECT_NEAR(flight.result.segments[i].end_s, expected[i].end_s, 1e-6);
    EXPECT_NEAR(flight.result.segments[i].mass_kg, expected[i].mass_kg, 1e-9);
  }
  EXPECT_EQ(flight.result.segments[3].mass_kg, 1.711);  // 1.315 kg + the 396 g payload (thesis table 6.4)
}

TEST(FlightSimulator, AirborneManifestSpansRunFromLiftOffToBeforeTouchdown) {
  pe::sim::FlightProfile profile = defaultProfile();
  profile.manifest_spans = pe::sim::ManifestSpans::kAirborne;
  const Flight flight = fly(profile);
  // By hand from the schedule. Segment 1 takes off empty: the feet leave the ground as the climb
  // starts after the 2 s spin-up, and the span starts the 8 s settle time later; segment 7 lands
  // from 0.2 m, already below the 0.32 m at which the feet come within 0.2 m of the ground, so
  // the span ends as the landing starts. Segment 9 takes off with the 396 g payload, whose 1 m
  // cable from 4 cm under base_link is taut at 1.04 m, 0.92 s into the 1 m/s climb; segment 11
  // lands from 2.5 m at 0.6 m/s and brings the payload within 0.2 m of the ground 2.1 s later.
  // The 0.8 m/s descent of segment 5 to 0.2 m overshoots by 8 cm, onto the feet: the ground
  // carries part of the weight for a moment, which splits the first stretch there, the second
  // part starting the settle time after the touch.
  const std::vector<pe::sim::ScheduledSegment>& s = flight.schedule;
  ASSERT_EQ(s[1].segment.kind, pe::sim::SegmentKind::kTakeoff);
  ASSERT_EQ(s[5].segment.kind, pe::sim::SegmentKind::kDescend);
  ASSERT_EQ(s[7].segment.kind, pe::sim::SegmentKind::kLand);
  ASSERT_EQ(s[9].segment.kind, pe::sim::SegmentKind::kTakeoff);
  ASSERT_EQ(s[11].segment.kind, pe::sim::SegmentKind::kLand);
  const std::vector<pe::ManifestSegment>& spans = flight.result.segments;
  ASSERT_EQ(spans.size(), 3u);
  EXPECT_NEAR(spans[0].start_s, s[1].start_s + 2.0 + 8.0, 1e-6);
  EXPECT_GT(spans[0].end_s, s[5].end_s - 0.5);
  EXPECT_LT(spans[0].end_s, s[5].end_s + 1.0);
  EXPECT_GT(spans[1].start_s, spans[0].end_s + 8.0);
  EXPECT_LT(spans[1].start_s, spans[0].end_s + 9.0);
  EXPECT_NEAR(spans[1].end_s, s[7].start_s, 1e-6);
  EXPECT_NEAR(spans[2].start_s, s[9].start_s + 2.0 + 0.92 + 8.0, 1e-6);
  EXPECT_NEAR(spans[2].end_s, s[11].start_s + 2.1, 1e-6);
  EXPECT_EQ(spans[0].mass_kg, 1.315);
  EXPECT_EQ(spans[1].mass_kg, 1.315);
  EXPECT_EQ(spans[2].mass_kg, 1.711);
  // The first span holds the climb to 5 m and most of the descent, not only the hovers.
  EXPECT_LT(spans[0].start_s, s[3].start_s);
  EXPECT_GT(spans[0].end_s, s[5].start_s + 5.0);
  // Throughout each span the weighed mass is in the air: the feet clear the ground, a payload
  // hangs on a taut cable, and the rotors' thrust averages the weight (the climbs and descents
  // cancel; tilt stays within a degree, drag is a few grams).
  for (const pe::ManifestSegment& span : spans) {
    const bool loaded = span.mass_kg > 1.315;
    double thrust = 0.0;
    int n = 0;
    forSegment(flight.sink.truths, span, [&](const pe::sim::TruthSample& t) {
      // (At a span's end the ground may be touched: the span stops there.)
      if (t.time_s < span.end_s) {
        EXPECT_GT(t.height_m, loaded ? 1.1 : 0.12) << t.time_s;
      }
      if (loaded) {
        EXPECT_GT(t.cable_tension_n, 0.0) << t.time_s;
      }
      EXPECT_DOUBLE_EQ(t.total_mass_kg, span.mass_kg);
      for (const pe::sim::MotorTruth& motor : t.motors) thrust += motor.thrust_n;
      ++n;
    });
    EXPECT_NEAR(thrust / n, span.mass_kg * pe::kStandardGravity, 0.005 * span.mass_kg * pe::kStandardGravity);
  }
}

TEST(FlightSimulator, HoldsTheCommandedHeights) {
  const Flight& flight = defaultFlight();
  const double targets[] = {2.0, 5.0, 0.2, 2.5};
  for (std::size_t i = 0; i < 4; ++i) {
    double sum = 0.0, worst = 0.0;
    int n = 0;
    forSegment(flight.sink.truths, flight.result.segments[i], [&](const pe::sim::TruthSample& t) {
      sum += t.height_m;
      worst = std::max(worst, std::fabs(t.height_m - targets[i]));
      ++n;
    });
    EXPECT_NEAR(sum / n, targets[i], 0.02) << "hover " << i;
    EXPECT_LT(worst, 0.05) << "hover " << i;
  }
}

TEST(FlightSimulator, TheThesisQuadHoversBetween1600And1750Us) {
  const Flight& flight = defaultFlight();
  for (std::size_t i = 0; i < 3; ++i) {  // the empty hovers
    double sum = 0.0;
    int n = 0;
    forSegment(flight.sink.rc_out, flight.result.segments[i], [&](const pe::sim::RcOutSample& s) {
      for (int k = 0; k < 4; ++k) sum += s.channels[k];
      n += 4;
    });
    EXPECT_GT(sum / n, 1600.0) << "hover " << i;
    EXPECT_LT(sum / n, 1750.0) << "hover " << i;
  }
}

TEST(FlightSimulator, TrueThrustSumsToTheWeightInHover) {
  const Flight& flight = defaultFlight();
  for (const pe::ManifestSegment& segment : flight.result.segments) {
    double sum = 0.0;
    int n = 0;
    forSegment(flight.sink.truths, segment, [&](const pe::sim::TruthSample& t) {
      for (const pe::sim::MotorTruth& motor : t.motors) sum += motor.thrust_n;
      ++n;
    });
    // Tilt in hover is below a degree: the thrust along the rotor axes is the weight to 0.3 %.
    EXPECT_NEAR(sum / n, segment.mass_kg * pe::kStandardGravity, 0.003 * segment.mass_kg * pe::kStandardGravity);
  }
}

TEST(FlightSimulator, ThePendulumPayloadsWeightAppearsInTheTotal) {
  const Flight& flight = defaultFlight();
  const pe::ManifestSegment& loaded = flight.result.segments[3];
  double tension = 0.0, thrust = 0.0;
  int n = 0;
  forSegment(flight.sink.truths, loaded, [&](const pe::sim::TruthSample& t) {
    EXPECT_EQ(t.payload_mass_kg, 0.396);
    EXPECT_DOUBLE_EQ(t.total_mass_kg, 1.315 + 0.396);
    tension += t.cable_tension_n;
    for (const pe::sim::MotorTruth& motor : t.motors) thrust += motor.thrust_n;
    ++n;
  });
  EXPECT_NEAR(tension / n, 0.396 * pe::kStandardGravity, 0.01 * 0.396 * pe::kStandardGravity);
  EXPECT_NEAR(thrust / n - tension / n, 1.315 * pe::kStandardGravity, 0.005 * 1.315 * pe::kStandardGravity);
  // Landed, the payload rests on the ground and the cable is slack.
  for (const pe::sim::TruthSample& t : flight.sink.truths) {
    if (t.payload_mass_kg > 0.0 && t.time_s < loaded.start_s - 20.0) {
      ASSERT_LT(t.height_m, 0.2);
      ASSERT_EQ(t.cable_tension_n, 0.0);
    }
  }
}

TEST(FlightSimulator, TheCentreOfThrustLiesUnderTheCentreOfGravity) {
  // The battery sits 8 mm forward and 5 mm right: the front-right motor (1) works hardest, the
  // rear-left (2) least, and the thrust-weighted rotor position is the centre of gravity.
  const Flight& flight = defaultFlight();
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(defaultProfile().vehicle.urdf_path);
  const Eigen::Vector3d cog = vehicle.empty_mass->centre_of_mass_m + defaultProfile().vehicle.centre_of_mass_offset_m;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  double total = 0.0;
  std::vector<double> mean(4, 0.0);
  forSegment(flight.sink.truths, flight.result.segments[1], [&](const pe::sim::TruthSample& t) {
    for (int k = 0; k < 4; ++k) {
      moment += t.motors[k].thrust_n * vehicle.rotors[k].position_m.head<2>();
      total += t.motors[k].thrust_n;
      mean[k] += t.motors[k].thrust_n;
    }
  });
  EXPECT_NEAR(moment.x() / total, cog.x(), 0.001);
  EXPECT_NEAR(moment.y() / total, cog.y(), 0.001);
  EXPECT_EQ(std::max_element(mean.begin(), mean.end()) - mean.begin(), 0);
  EXPECT_EQ(std::min_element(mean.begin(), mean.end()) - mean.begin(), 1);
}

TEST(FlightSimulator, StreamsKeepTheirRatesFromTheFirstMessage) {
  const Flight& flight = defaultFlight();
  const double duration = flight.result.duration_s;
  const auto expected = [&](double rate_hz) {
    return static_cast<std::size_t>(std::floor(duration * rate_hz + 1e-6)) + 1;
  };
  const pe::sim::FlightSensorParams sensors;
  EXPECT_EQ(flight.sink.rc_out.size(), expected(50.0));
  EXPECT_EQ(flight.sink.truths.size(), expected(50.0));
  EXPECT_EQ(flight.sink.batteries.size(), expected(sensors.battery_rate_hz));
  EXPECT_EQ(flight.sink.imus.size(), expected(sensors.imu_rate_hz));
  EXPECT_EQ(flight.sink.poses.size(), expected(sensors.pose_rate_hz));
  EXPECT_EQ(flight.sink.velocities.size(), expected(sensors.pose_rate_hz));
  EXPECT_EQ(flight.sink.pressures.size(), expected(sensors.pressure_rate_hz));
  EXPECT_EQ(flight.sink.air_temperatures.size(), expected(sensors.air_temperature_rate_hz));
  EXPECT_EQ(flight.sink.ranges.size(), expected(sensors.rangefinder_rate_hz));
  EXPECT_EQ(flight.sink.motor_temperatures.size(), expected(sensors.motor_temperature_rate_hz));
  EXPECT_EQ(flight.sink.rc_out.front().time_s, 0.0);
  EXPECT_EQ(flight.sink.imus.front().time_s, 0.0);
  EXPECT_NEAR(flight.sink.poses[3].time_s, 0.1, 0.002);  // 30 Hz on a 2 ms step
}

TEST(FlightSimulator, SensorsReadThePhysicalState) {
  const Flight& flight = defaultFlight();
  const pe::ManifestSegment& high = flight.result.segments[1];  // 5 m
  const pe::ManifestSegment& low = flight.result.segments[0];   // 2 m
  const auto mean = [](const std::vector<double>& values) {
    double sum = 0.0;
    for (double v : values) sum += v;
    return sum / values.size();
  };
  std::vector<double> range_high, range_low, pressure_high, pressure_low, accel_z, pose_z;
  forSegment(flight.sink.ranges, high, [&](const pe::sim::RangeSample& s) { range_high.push_back(s.range_m); });
  forSegment(flight.sink.ranges, low, [&](const pe::sim::RangeSample& s) { range_low.push_back(s.range_m); });
  forSegment(flight.sink.pressures, high, [&](const pe::sim::ScalarSample& s) { pressure_high.push_back(s.value); });
  forSegment(flight.sink.pressures, low, [&](const pe::sim::ScalarSample& s) { pressure_low.push_back(s.value); });
  forSegment(flight.sink.imus, high,
             [&](const pe::sim::ImuSample& s) { accel_z.push_back(s.linear_acceleration_m_s2.z()); });
  forSegment(flight.sink.poses, high, [&](const pe::sim::PoseSample& s) { pose_z.push_back(s.position_m.z()); });
  EXPECT_NEAR(mean(range_high), 5.0, 0.02);
  EXPECT_NEAR(mean(range_low), 2.0, 0.02);
  // Air of 1.196 kg/m^3: 11.73 Pa per metre.
  EXPECT_NEAR(mean(pressure_low) - mean(pressure_high), 3.0 * 1.196 * pe::kStandardGravity, 1.5);
  EXPECT_NEAR(mean(accel_z), pe::kStandardGravity, 0.05);
  EXPECT_NEAR(mean(pose_z), 5.0 - 0.12, 0.02);  // local position starts at 0 on the ground
  // Standing on its gear before take-off, the accelerometer reads g from the first message on.
  EXPECT_NEAR(flight.sink.imus.front().linear_acceleration_m_s2.z(), pe::kStandardGravity, 0.25);
  // On the ground the rangefinder (0.1 m minimum) still reads the 0.12 m landing gear.
  EXPECT_NEAR(flight.sink.ranges.front().range_m, 0.12, 0.05);
}

TEST(FlightSimulator, Px4AndArduPilotConventions) {
  const Flight& px4 = defaultFlight();
  EXPECT_EQ(px4.sink.rc_out.front().channels, (std::vector<std::uint16_t>{900, 900, 900, 900, 0, 0, 0, 0}));
  const pe::ManifestSegment& hover = px4.result.segments[0];
  forSegment(px4.sink.batteries, hover, [](const pe::sim::BatterySample& s) { EXPECT_LT(s.current_a, -10.0); });

  pe::sim::FlightProfile profile = defaultProfile();
  profile.autopilot.flavour = pe::sim::AutopilotFlavour::kArduPilot;
  profile.autopilot.disarmed_pwm_us = 0.0;
  const Flight ardupilot = fly(profile);
  EXPECT_EQ(ardupilot.sink.rc_out.front().channels, (std::vector<std::uint16_t>{0, 0, 0, 0, 0, 0, 0, 0}));
  forSegment(ardupilot.sink.batteries, hover, [](const pe::sim::BatterySample& s) { EXPECT_GT(s.current_a, 10.0); });
}

TEST(FlightSimulator, TheSeedFixesTheFlight) {
  pe::sim::FlightProfile profile = defaultProfile();
  profile.segments.resize(4);  // wait, take off, hover, climb
  profile.segments.push_back({pe::sim::SegmentKind::kLand, 0.0, 0.0, 1.0, 0.0});
  const Flight a = fly(profile, 4);
  const Flight b = fly(profile, 4);
  const Flight c = fly(profile, 5);
  ASSERT_EQ(a.sink.imus.size(), b.sink.imus.size());
  for (std::size_t i = 0; i < a.sink.imus.size(); ++i) {
    ASSERT_EQ(a.sink.imus[i].linear_acceleration_m_s2, b.sink.imus[i].linear_acceleration_m_s2);
  }
  EXPECT_NE(a.sink.imus[100].linear_acceleration_m_s2, c.sink.imus[100].linear_acceleration_m_s2);
  // Noise is on the sensors only: the flown trajectory is the same.
  EXPECT_EQ(a.sink.truths.back().height_m, c.sink.truths.back().height_m);
}

TEST(FlightSimulator, RefusesAPayloadTooHeavyToHover) {
  // 2.515 kg / 4 rotors x g = 6.17 N, beyond 80 % of the ~697 g a rotor gives at full pulse width.
  pe::sim::FlightProfile profile = defaultProfile();
  profile.segments[8].payload_mass_kg = 1.2;
  EXPECT_EQ(refusal(profile),
            repoPath("config/sim/default_flight.yaml") +
                ": segments[8].mass_kg: 2.52 kg needs 6.17 N per rotor, more than 80 % of the 6.84 N each gives at "
                "1950 us from 12.5 V");
}

TEST(FlightSimulator, RefusesAFlightLongerThanTheBattery) {
  pe::sim::FlightProfile profile = defaultProfile();
  // 13 % of 4 Ah above the 2 % floor at the ~13 A of the empty hovers: about 144 s.
  profile.vehicle.battery_initial_soc = 0.15;
  EXPECT_EQ(refusal(profile), repoPath("config/sim/default_flight.yaml") +
                                  ": vehicle.battery_initial_soc: the battery is empty 142 s into the flight");
}

TEST(FlightSimulator, RefusesAHoverTheVehicleCannotReach) {
  // 5 m/s to 50 m is beyond the autopilot's 2 m/s climb limit: after 12 s of climbing the vehicle is at
  // 17 m, and its hover would not be where the manifest says.
  pe::sim::FlightProfile profile = defaultProfile();
  profile.segments = {{pe::sim::SegmentKind::kTakeoff, 0.0, 50.0, 5.0, 0.0},
                      {pe::sim::SegmentKind::kHover, 0.5, 0.0, 0.0, 0.0},
                      {pe::sim::SegmentKind::kLand, 0.0, 0.0, 5.0, 0.0}};
  EXPECT_EQ(refusal(profile), repoPath("config/sim/default_flight.yaml") +
                                  ": segments[1].type: the vehicle ended its hover at 17 m instead of 50 m");
}

TEST(FlightSimulator, ALightPayloadOnAStiffDampedCableHangsSteadily) {
  // 10 g on the default cable (1000 N/m, 10 N s/m) and on the stiffest, most damped one a profile
  // may have (1e5 N/m, 1000 N s/m): stretch modes of 316 and 3162 rad/s and damping rates c/m of
  // 1000 and 1e5 /s, against a 2 ms step. The cable must carry the payload's weight, steadily.
  for (const auto& [stiffness, damping] : {std::pair{1000.0, 10.0}, std::pair{1e5, 1e3}}) {
    pe::sim::FlightProfile profile = defaultProfile();
    profile.cable.stiffness_n_per_m = stiffness;
    profile.cable.damping_n_s_per_m = damping;
    profile.segments = {{pe::sim::SegmentKind::kWait, 1.0, 0.0, 0.0, 0.0},
                        {pe::sim::SegmentKind::kPayload, 2.0, 0.0, 0.0, 0.01},
                        {pe::sim::SegmentKind::kTakeoff, 0.0, 2.5, 1.0, 0.0},
                        {pe::sim::SegmentKind::kHover, 20.0, 0.0, 0.0, 0.0},
                        {pe::sim::SegmentKind::kLand, 0.0, 0.0, 1.0, 0.0}};
    const Flight flight = fly(profile);
    ASSERT_EQ(flight.result.segments.size(), 1u);
    double tension = 0.0, worst_height = 0.0;
    int n = 0;
    forSegment(flight.sink.truths, flight.result.segments[0], [&](const pe::sim::TruthSample& t) {
      tension += t.cable_tension_n;
      worst_height = std::max(worst_height, std::fabs(t.height_m - 2.5));
      ++n;
    });
    EXPECT_NEAR(tension / n, 0.01 * pe::kStandardGravity, 0.01 * 0.01 * pe::kStandardGravity) << stiffness;
    EXPECT_LT(worst_height, 0.05) << stiffness;
  }
}

TEST(FlightSimulator, RefusesAFlightThatDiverges) {
  // A vehicle whose inertia is a millionth of the quad's: the 2 ms step cannot follow its
  // rotation (angular damping alone has the rate 0.002 N m s / 1e-8 kg m^2 = 2e5 /s).
  pe::sim::FlightProfile profile = defaultProfile();
  pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  vehicle.empty_mass->inertia_kg_m2 *= 1e-6;
  RecordingFlightSink sink;
  try {
    pe::sim::simulateFlight(thesisParams(), {}, profile, vehicle, 1, &sink);
    ADD_FAILURE() << "accepted";
  } catch (const pe::SimulationError& e) {
    EXPECT_EQ(std::string(e.what()),
              repoPath("config/sim/default_flight.yaml") + ": the simulation diverged at t = 0.016 s");
  }
}

TEST(FlightSimulator, RefusesALandingThatDoesNotLandAlsoAtTheEnd) {
  // Landing from 20 m at 5 m/s: the autopilot descends at 2 m/s at most, so 4 s after the scripted
  // descent the vehicle is still about 4 m up. Checked where the landing ends the profile and where
  // it does not.
  pe::sim::FlightProfile profile = defaultProfile();
  profile.segments = {{pe::sim::SegmentKind::kWait, 1.0, 0.0, 0.0, 0.0},
                      {pe::sim::SegmentKind::kTakeoff, 0.0, 20.0, 2.0, 0.0},
                      {pe::sim::SegmentKind::kLand, 0.0, 0.0, 5.0, 0.0}};
  const std::string expected = repoPath("config/sim/default_flight.yaml") +
                               ": segments[2].type: the vehicle had not landed and disarmed 4 s after its descent";
  EXPECT_EQ(refusal<pe::SimulationError>(profile), expected);
  profile.segments.push_back({pe::sim::SegmentKind::kWait, 1.0, 0.0, 0.0, 0.0});
  EXPECT_EQ(refusal<pe::SimulationError>(profile), expected);
}

TEST(FlightSimulator, RefusesAFlightThatFlipsOverRatherThanCountItLanded) {
  // The centre of gravity 10 cm out towards the front-left motor, beyond what the attitude
  // integrators can hold: the quad leans after take-off and rolls over on its left side as the
  // landing begins. Upside down on the ground it comes to rest low and still, which the land
  // detector took for landed: without the attitude check this flight was accepted.
  pe::sim::FlightProfile profile = defaultProfile();
  profile.vehicle.centre_of_mass_offset_m = Eigen::Vector3d(0.07, 0.07, 0.0);
  profile.segments = {{pe::sim::SegmentKind::kWait, 2.0, 0.0, 0.0, 0.0},
                      {pe::sim::SegmentKind::kTakeoff, 0.0, 1.0, 1.0, 0.0},
                      {pe::sim::SegmentKind::kLand, 0.0, 0.0, 0.5, 0.0},
                      {pe::sim::SegmentKind::kWait, 1.0, 0.0, 0.0, 0.0}};
  EXPECT_EQ(refusal<pe::SimulationError>(profile),
            repoPath("config/sim/default_flight.yaml") +
                ": segments[2].type: the vehicle flipped over: roll -178 deg, pitch 1 deg at t = 5.614 s, beyond 60 "
                "deg since 5.314 s");
}

TEST(FlightSimulator, AWeakPropellerIsMadeUpByItsMotorAndTheVehicleHoldsItsHeight) {
  // Motor 3's propeller makes 85 % of the thrust at the same speed (and 82 % of the torque). The
  // attitude integrators, knowing nothing of it, raise its pulse width until the moments balance
  // again: its rotor spins sqrt(1/0.85) = 8.5 % faster for the same share of the weight, and the
  // vehicle, with the default flight's offset centre of gravity too, holds its heights.
  pe::sim::FlightProfile profile = defaultProfile();
  profile.faults.weak_propeller = pe::sim::PropellerFault{3, 0.85};
  const Flight weak = fly(profile);
  const Flight& intact = defaultFlight();
  ASSERT_EQ(weak.result.segments.size(), 4u);
  const double targets[] = {2.0, 5.0, 0.2, 2.5};
  for (std::size_t i = 0; i < 4; ++i) {
    const pe::ManifestSegment& segment = weak.result.segments[i];
    std::vector<double> pwm(4, 0.0), intact_pwm(4, 0.0), rpm(4, 0.0), intact_rpm(4, 0.0);
    double height = 0.0, worst = 0.0, thrust = 0.0;
    int n = 0;
    forSegment(weak.sink.truths, segment, [&](const pe::sim::TruthSample& t) {
      for (int k = 0; k < 4; ++k) {
        pwm[k] += t.motors[k].pwm_us;
        rpm[k] += t.motors[k].rpm;
        thrust += t.motors[k].thrust_n;
      }
      height += t.height_m;
      worst = std::max(worst, std::fabs(t.height_m - targets[i]));
      ++n;
    });
    int intact_n = 0;
    forSegment(intact.sink.truths, intact.result.segments[i], [&](const pe::sim::TruthSample& t) {
      for (int k = 0; k < 4; ++k) {
        intact_pwm[k] += t.motors[k].pwm_us;
        intact_rpm[k] += t.motors[k].rpm;
      }
      ++intact_n;
    });
    for (int k = 0; k < 4; ++k) {
      pwm[k] /= n;
      rpm[k] /= n;
      intact_pwm[k] /= intact_n;
      intact_rpm[k] /= intact_n;
    }
    EXPECT_GT(pwm[2], intact_pwm[2] + 25.0) << "hover " << i;
    for (int k : {0, 1, 3}) EXPECT_GT(pwm[2], pwm[k] + 25.0) << "hover " << i << ", motor " << k + 1;
    EXPECT_NEAR(rpm[2] / intact_rpm[2], 1.085, 0.03) << "hover " << i;
    EXPECT_NEAR(height / n, targets[i], 0.02) << "hover " << i;
    EXPECT_LT(worst, 0.05) << "hover " << i;
    EXPECT_NEAR(thrust / n, segment.mass_kg * pe::kStandardGravity, 0.003 * segment.mass_kg * pe::kStandardGravity)
        << "hover " << i;
  }
  EXPECT_EQ(refusal<pe::ConfigError>([&] {
              pe::sim::FlightProfile five = profile;
              five.faults.weak_propeller->motor = 5;
              return five;
            }()),
            repoPath("config/sim/default_flight.yaml") +
                ": faults.weak_propeller.motor: 5 is not a motor of " + repoPath("config/sim/../f450_quad.urdf") +
                " (4 rotors)");
}

TEST(FlightSimulator, AWornPropellerSpinsAsFastAsAChippedOneButDrawsMoreCurrent) {
  // Both make 85 % of the thrust at the same speed, so both spin faster in hover (within 5 %); the
  // chipped one (smaller) absorbs less torque than intact at that speed, the worn one (its profile
  // drag kept) more: its motor draws more current, which moves the yaw balance the other way.
  const auto hover = [](pe::sim::PropellerDamage damage) {
    pe::sim::FlightProfile profile = defaultProfile();
    profile.faults.weak_propeller = pe::sim::PropellerFault{3, 0.85, damage};
    const Flight flight = fly(profile);
    double rpm = 0.0, current = 0.0, others = 0.0, height = 0.0;
    int n = 0;
    forSegment(flight.sink.truths, flight.result.segments[0], [&](const pe::sim::TruthSample& t) {
      rpm += t.motors[2].rpm;
      current += t.motors[2].current_a;
      others += (t.motors[0].current_a + t.motors[1].current_a + t.motors[3].current_a) / 3.0;
      height += t.height_m;
      ++n;
    });
    return std::array<double, 4>{rpm / n, current / n, others / n, height / n};
  };
  const std::array<double, 4> chipped = hover(pe::sim::PropellerDamage::kChipped);
  const std::array<double, 4> worn = hover(pe::sim::PropellerDamage::kWorn);
  EXPECT_NEAR(worn[0] / chipped[0], 1.0, 0.05);
  EXPECT_GT(worn[1], 1.08 * chipped[1]);  // measured 2026-11-25: 3.79 A against 3.35 A
  EXPECT_GT(worn[1], worn[2]);
  EXPECT_NEAR(worn[3], 2.0, 0.02);
}

TEST(FlightSimulator, RefusesAVehicleItCannotFlyNamingItsUrdf) {
  const pe::sim::FlightProfile profile = defaultProfile();
  const pe::Vehicle quad = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  const auto refused = [&](const pe::Vehicle& vehicle) {
    try {
      pe::sim::checkFlight(thesisParams(), {}, profile, vehicle);
    } catch (const pe::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  pe::Vehicle massless = quad;
  massless.empty_mass.reset();
  EXPECT_EQ(refused(massless), repoPath("config/sim/../f450_quad.urdf") +
                                   ": the flight simulator needs the rotors' positions and the mass properties of the "
                                   "vehicle (a URDF with rotor joints and <inertial> elements)");
  pe::Vehicle one_way = quad;  // every propeller turning the same way: no yaw control
  for (pe::Rotor& rotor : one_way.rotors) rotor.spin_direction = 1;
  EXPECT_EQ(refused(one_way), repoPath("config/sim/../f450_quad.urdf") +
                                  ": the rotor layout cannot control roll, pitch, yaw and thrust independently");
  EXPECT_EQ(refused(quad), "accepted");
}

// An effects file's per-ESC offsets for another count of ESCs than the vehicle's rotors is
// refused before anything flies.
TEST(FlightSimulator, RefusesEscOffsetsForAnotherCountOfEscs) {
  const pe::sim::FlightProfile profile = defaultProfile();
  const pe::Vehicle quad = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  pe::sim::SimEffects effects;
  effects.esc_offset_us = 10.0;
  effects.esc_offset_per_esc_us = {1.0, -1.0};
  try {
    pe::sim::checkFlight(thesisParams(), effects, profile, quad);
    FAIL() << "two ESC offsets were accepted for four rotors";
  } catch (const pe::FieldError& e) {
    EXPECT_EQ(std::string(e.what()), "esc_offset.per_esc_us: has 2 entries for the vehicle's 4 rotors");
  }
  effects.esc_offset_per_esc_us = {1.0, -1.0, 2.0, 0.0};
  EXPECT_NO_THROW(pe::sim::checkFlight(thesisParams(), effects, profile, quad));
}

TEST(FlightSimulator, FliesAHexacopter) {
  // Six rotors 0.3 m out at 60 deg spacing, alternating spin, 1.9 kg: the geometric mixer handles
  // six motors, the vehicle holds its height, its thrust balances the weight, the centre of thrust
  // lies under the centre of gravity (the profile's 8 mm / -5 mm offset), and rc/out carries six
  // motor channels of its eight.
  pe::Vehicle hexa;
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < 6; ++k) {
    pe::Rotor rotor;
    rotor.name = "rotor_" + std::to_string(k + 1);
    const double angle = pi / 6.0 + k * pi / 3.0;
    rotor.position_m = Eigen::Vector3d(0.3 * std::cos(angle), 0.3 * std::sin(angle), 0.035);
    rotor.spin_direction = k % 2 == 0 ? 1 : -1;
    hexa.rotors.push_back(rotor);
  }
  pe::MassProperties mass;
  mass.mass_kg = 1.9;
  mass.inertia_kg_m2 = Eigen::Vector3d(0.02, 0.02, 0.035).asDiagonal();
  hexa.empty_mass = mass;
  pe::sim::FlightProfile profile = defaultProfile();
  profile.segments = {{pe::sim::SegmentKind::kWait, 1.0, 0.0, 0.0, 0.0},
                      {pe::sim::SegmentKind::kTakeoff, 0.0, 2.0, 1.0, 0.0},
                      {pe::sim::SegmentKind::kHover, 25.0, 0.0, 0.0, 0.0},
                      {pe::sim::SegmentKind::kLand, 0.0, 0.0, 1.0, 0.0}};
  Flight flight;
  flight.result = pe::sim::simulateFlight(thesisParams(), {}, profile, hexa, 1, &flight.sink);
  ASSERT_EQ(flight.result.segments.size(), 1u);
  const pe::ManifestSegment& hover = flight.result.segments[0];
  EXPECT_EQ(hover.mass_kg, 1.9);
  double height = 0.0, worst = 0.0, total = 0.0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  int n = 0;
  forSegment(flight.sink.truths, hover, [&](const pe::sim::TruthSample& t) {
    ASSERT_EQ(t.motors.size(), 6u);
    height += t.height_m;
    worst = std::max(worst, std::fabs(t.height_m - 2.0));
    for (int k = 0; k < 6; ++k) {
      total += t.motors[k].thrust_n;
      moment += t.motors[k].thrust_n * hexa.rotors[k].position_m.head<2>();
    }
    ++n;
  });
  EXPECT_NEAR(height / n, 2.0, 0.02);
  EXPECT_LT(worst, 0.05);
  EXPECT_NEAR(total / n, 1.9 * pe::kStandardGravity, 0.003 * 1.9 * pe::kStandardGravity);
  EXPECT_NEAR(moment.x() / total, 0.008, 0.001);
  EXPECT_NEAR(moment.y() / total, -0.005, 0.001);
  forSegment(flight.sink.rc_out, hover, [](const pe::sim::RcOutSample& s) {
    ASSERT_EQ(s.channels.size(), 8u);
    for (int k = 0; k < 6; ++k) {
      EXPECT_GT(s.channels[k], 1500);
      EXPECT_LT(s.channels[k], 1850);
    }
    EXPECT_EQ(s.channels[6], 0);
    EXPECT_EQ(s.channels[7], 0);
  });
  EXPECT_EQ(flight.sink.rc_out.front().channels, (std::vector<std::uint16_t>{900, 900, 900, 900, 900, 900, 0, 0}));
}

TEST(FlightSimulator, TheAvionicsDrawIsSensedButNotSeenByTheEscs) {
  pe::sim::FlightProfile profile = defaultProfile();
  profile.vehicle.avionics_current_a = 1.5;
  const Flight flight = fly(profile);
  // The battery current the sensor reports is the ESCs' input current plus the avionics' draw.
  for (std::size_t i = 0; i < flight.sink.truths.size(); i += 500) {
    const pe::sim::TruthSample& t = flight.sink.truths[i];
    double escs = 0.0;
    for (const pe::sim::MotorTruth& motor : t.motors) escs += motor.current_a;
    EXPECT_NEAR(t.battery_current_a, escs + 1.5, 1e-9) << "at " << t.time_s << " s";
  }
  profile.vehicle.avionics_current_a = 6.0;
  EXPECT_EQ(refusal(profile), "vehicle.avionics_current_a: 6 is outside 0..5 A");
}

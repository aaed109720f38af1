// A dynamic flight as users fly it (take-off, short hovers, climbs and descents, straight legs, landing), weighed
// from take-off to landing: the rotors' spin-up lag is identified from the flight itself (the
// simulator's lag comes from its motors' and propellers' inertia, not from any formula of the
// diagnosis), and with it the transient blocks count without biasing the gap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>
#include <random>
#include <string>
#include <vector>

#include "propulsion_estimator/gap/airborne_stretch.h"
#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/gap/rotor_lag.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "recording_flight_sink.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace gap = propulsion_estimator::gap;

namespace {

// The vehicle, its autopilot and its manifest, before a profile's segments.
const std::string kVehicleAndManifest =
    "autopilot: {flavour: px4, pwm_min_us: 1100, pwm_max_us: 1950, disarmed_pwm_us: 900, rc_out_rate_hz: RATE}\n"
    "vehicle: {urdf: URDF, centre_of_mass_offset_m: [0.008, -0.005, 0], landing_gear: {height_m: 0.12, "
    "half_width_m: 0.12}, drag_area_m2: 0.04, battery_initial_soc: 0.95}\n"
    "payload_cable: {length_m: 0.15, attach_point_m: [0, 0, -0.04], stiffness_n_per_m: 1000, damping_n_s_per_m: 10}\n"
    "manifest: {settle_s: 2, spans: SPANS}\n"
    "segments:\n";

const std::string kProfile = kVehicleAndManifest +
    "  - {type: wait, duration_s: 3}\n"
    "  - {type: payload, mass_kg: PAYLOAD, duration_s: 2}\n"
    "  - {type: takeoff, height_m: 2.0, rate_m_s: 1.5}\n"
    "  - {type: hover, duration_s: HOVER}\n"
    "  - {type: move, east_m: 24, north_m: 0, speed_m_s: 3}\n"
    "  - {type: climb, height_m: 6.0, rate_m_s: 2.0}\n"
    "  - {type: hover, duration_s: HOVER}\n"
    "  - {type: move, east_m: -18, north_m: 18, speed_m_s: 4}\n"
    "  - {type: descend, height_m: 1.5, rate_m_s: 2.0}\n"
    "  - {type: hover, duration_s: HOVER}\n"
    "  - {type: climb, height_m: 4.0, rate_m_s: 2.0}\n"
    "  - {type: descend, height_m: 1.0, rate_m_s: 1.5}\n"
    "  - {type: hover, duration_s: HOVER}\n"
    "  - {type: land, rate_m_s: 0.6}\n"
    "  - {type: wait, duration_s: 2}\n";

// A flight that hovers twice near the ground (its rotors 0.3 and 0.4 m up, within two rotor
// diameters) and twice well above it, without a payload.
const std::string kNearTheGroundProfile = kVehicleAndManifest +
    "  - {type: wait, duration_s: 3}\n"
    "  - {type: takeoff, height_m: 3.0, rate_m_s: 1.0}\n"
    "  - {type: hover, duration_s: HOVER}\n"
    "  - {type: descend, height_m: 0.3, rate_m_s: 1.0}\n"
    "  - {type: hover, duration_s: LOW}\n"
    "  - {type: climb, height_m: 5.0, rate_m_s: 1.5}\n"
    "  - {type: hover, duration_s: HOVER}\n"
    "  - {type: descend, height_m: 0.4, rate_m_s: 1.0}\n"
    "  - {type: hover, duration_s: LOW}\n"
    "  - {type: land, rate_m_s: 0.5}\n"
    "  - {type: wait, duration_s: 2}\n";

// How a dynamic flight is flown and weighed.
struct Script {
  std::string profile = kProfile;  // kProfile, or kNearTheGroundProfile (no payload)
  std::string spans = "airborne";  // the manifest: "airborne" (take-off to landing) or "hovers"
  double payload_kg = 0.0;  // 0 for none
  double hover_s = 5.0;  // each of its four hovers
  double low_hover_s = 8.0;  // kNearTheGroundProfile: each of its two hovers near the ground
  int rc_out_rate_hz = 50;  // how often the log holds the ESC commands
  pe::sim::SimEffects effects;  // what the surfaces leave out
};

void fill(std::string* text, const std::string& key, const std::string& value) {
  for (std::size_t at = text->find(key); at != std::string::npos; at = text->find(key)) {
    text->replace(at, key.size(), value);
  }
}

// The simulated flight as a log holds it (PX4's signs, the rangefinder's in-range readings).
pe::Flight simulateDynamicFlight(std::uint64_t seed, const Script& script = {}) {
  std::string text = script.profile;
  fill(&text, "URDF", repoPath("config/f450_quad.urdf"));
  fill(&text, "SPANS", script.spans);
  fill(&text, "PAYLOAD", std::to_string(script.payload_kg));
  fill(&text, "HOVER", std::to_string(script.hover_s));
  fill(&text, "LOW", std::to_string(script.low_hover_s));
  fill(&text, "RATE", std::to_string(script.rc_out_rate_hz));
  const pe::sim::FlightProfile profile = pe::sim::parseFlightProfileYaml(text, "dynamic.yaml");
  RecordingFlightSink sink;
  const pe::sim::FlightResult result =
      pe::sim::simulateFlight(pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")),
                              script.effects, profile, pe::loadVehicleUrdf(profile.vehicle.urdf_path), seed, &sink);
  pe::Flight flight;
  flight.name = "dynamic_" + std::to_string(seed) + ".bag";
  flight.streams.motors = 4;
  for (const auto& s : sink.rc_out) {
    pe::RcOutFrame frame;
    frame.time_s = s.time_s;
    for (int k = 0; k < 4; ++k) frame.pwm_us[k] = s.channels[k];
    flight.streams.rc_out.push_back(frame);
  }
  for (const auto& s : sink.batteries) flight.streams.battery.push_back({s.time_s, s.voltage_v, s.current_a});
  for (const auto& s : sink.imus) {
    flight.streams.imu.push_back({s.time_s, s.orientation, s.linear_acceleration_m_s2});
  }
  for (const auto& s : sink.velocities) {
    flight.streams.vertical_speed_m_s.push_back({s.time_s, s.linear_m_s.z()});
    flight.streams.horizontal_velocity.push_back({s.time_s, s.linear_m_s.x(), s.linear_m_s.y()});
  }
  for (const auto& s : sink.ranges) {
    if (std::isfinite(s.range_m)) flight.streams.input(pe::input::Scalar::kRangefinder).push_back({s.time_s, s.range_m});
  }
  flight.segments = result.segments;
  return flight;
}

struct Cut {
  int blocks = 0;      // cut from the weighed spans
  int steady = 0;      // within the steady bounds (DiagnosisConfig's defaults)
  int dynamic = 0;     // beyond them but within the dynamic bounds
  double dynamic_bias_pct = 0.0;  // the plain model's mean residual over the dynamic blocks, %
  double dynamic_rmse_pct = 0.0;  // and its root mean square, %
  double steady_bias_pct = 0.0;   // the mean residual over the steady blocks, %
  int moving = 0;                 // of the steady and dynamic ones, those moving faster than 1 m/s horizontally
  double moving_bias_pct = 0.0;   // the mean residual over those, %
};

Cut cut(const pe::Flight& flight, double time_constant_s) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const gap::ThrustViews views(model, 4);
  gap::BlockConfig config;
  config.rotor_time_constant_s = time_constant_s;
  const gap::FlightBlocks blocks =
      gap::cutIntoBlocks(flight, 0, pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf")), config, 0);
  const gap::DiagnosisConfig defaults;
  Cut result;
  for (const gap::Block& block : blocks.blocks) {
    ++result.blocks;
    const double residual = 100.0 * (views.pwmView(block, {}) / block.truth_n - 1.0);
    const bool used = gap::isQuasiSteady(block, defaults.dynamic_max_pwm_change_us, defaults.dynamic_max_accel_m_s2);
    if (used && block.signals.value(pe::effects::Signal::kHorizontalSpeed) > 1.0) {
      ++result.moving;
      result.moving_bias_pct += residual;
    }
    if (gap::isQuasiSteady(block, defaults.max_pwm_change_us, defaults.max_accel_m_s2)) {
      ++result.steady;
      result.steady_bias_pct += residual;
    } else if (gap::isQuasiSteady(block, defaults.dynamic_max_pwm_change_us, defaults.dynamic_max_accel_m_s2)) {
      ++result.dynamic;
      result.dynamic_bias_pct += residual;
      result.dynamic_rmse_pct += residual * residual;
    }
  }
  result.steady_bias_pct /= std::max(1, result.steady);
  result.moving_bias_pct /= std::max(1, result.moving);
  result.dynamic_bias_pct /= std::max(1, result.dynamic);
  result.dynamic_rmse_pct = std::sqrt(result.dynamic_rmse_pct / std::max(1, result.dynamic));
  return result;
}

}  // namespace

TEST(DynamicFlight, TheRotorLagIsIdentifiedFromTheFlight) {
  const pe::Flight flight = simulateDynamicFlight(1);
  const std::optional<gap::RotorLag> lag = gap::identifyRotorLag({flight}, 4, 1.0);
  ASSERT_TRUE(lag.has_value());
  // A 9.4 in propeller on a 2212 motor spins up in tens of milliseconds, not in none or in 0.3 s.
  EXPECT_GT(lag->time_constant_s, 0.02);
  EXPECT_LT(lag->time_constant_s, 0.15);
  EXPECT_GT(lag->fit_r2, 0.3);
}

TEST(DynamicFlight, WithTheLagModelledMostBlocksCountUnbiased) {
  const pe::Flight flight = simulateDynamicFlight(2);
  const std::optional<gap::RotorLag> lag = gap::identifyRotorLag({flight}, 4, 1.0);
  ASSERT_TRUE(lag.has_value());
  const Cut lagged = cut(flight, lag->time_constant_s);
  const Cut plain = cut(flight, 0.0);
  // At least half the weighed blocks count, and the transient ones do not move the gap.
  EXPECT_GE(2 * (lagged.steady + lagged.dynamic), lagged.blocks) << lagged.steady << " + " << lagged.dynamic;
  EXPECT_LT(std::abs(lagged.dynamic_bias_pct - lagged.steady_bias_pct), 1.0);
  // The straight legs count too: tilted, their thrust is taken along the rotors' axes, and with no
  // edgewise flow in this flight they err as the hovers do.
  EXPECT_GT(lagged.moving, 5);
  EXPECT_LT(std::abs(lagged.moving_bias_pct - lagged.steady_bias_pct), 1.0);
  std::printf("blocks %d: steady %d, dynamic %d, moving %d; bias steady %.2f %%, dynamic %.2f %%, moving %.2f %%\n",
              lagged.blocks, lagged.steady, lagged.dynamic, lagged.moving, lagged.steady_bias_pct,
              lagged.dynamic_bias_pct, lagged.moving_bias_pct);
  // The lag is what made them unusable: without it the transient blocks err about 4.5 times more
  // (measured 2026-11-25: 0.7 % against 3.2 % RMSE, 25 of 28 blocks, lag 75 ms with r^2 0.99).
  EXPECT_LT(lagged.dynamic_rmse_pct, 1.5);
  EXPECT_LT(lagged.dynamic_rmse_pct, 0.5 * plain.dynamic_rmse_pct);
}

namespace {

// Five flights with a 7 % thrust loss, `effects` besides, and payloads of 0-0.2 kg, from seed
// `first_seed` on, diagnosed twice: weighed from take-off to landing (most blocks transient, the
// lag identified) and on their hovers alone. The effects are selected on the steady blocks alone:
// hovers of 10 s give them enough to tell a thrust loss from an ESC offset (of 8 s, two seed sets
// of eight leave the two ambiguous).
struct BothWays {
  gap::Diagnosis airborne;
  gap::Diagnosis hovers;
};

// The flights as a user without hand-cut segments gives them: one mass per flight (a manifest's
// `mass_kg:`), the airborne stretch found in the log; each found stretch beside the simulator's.
std::vector<pe::Flight> weighedAsAWhole(std::vector<pe::Flight> flights, const pe::PropulsionModel& model) {
  for (pe::Flight& flight : flights) {
    std::vector<gap::AirborneStretch> found;
    const std::vector<pe::ManifestSegment> truth = flight.segments;
    flight.segments = gap::airborneSegments(flight.streams, model, {truth.front().mass_kg}, {}, &found);
    EXPECT_EQ(found.size(), 1u) << flight.name;
    // The simulator's span starts 2 s after the true lift-off (the profile's settle_s), the found
    // one settle_s (4 s) after the thrust first holds the vehicle; both end near touchdown.
    EXPECT_GE(flight.segments.front().start_s, truth.front().start_s) << flight.name;
    EXPECT_LE(flight.segments.front().start_s, truth.front().start_s + 4.0) << flight.name;
    EXPECT_NEAR(flight.segments.back().end_s, truth.back().end_s, 2.0) << flight.name;
  }
  return flights;
}

BothWays diagnoseBothWays(int first_seed, const pe::sim::SimEffects& effects, bool as_a_whole = false) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  std::vector<pe::Flight> airborne, hovers;
  for (int f = 0; f < 5; ++f) {
    Script script;
    script.payload_kg = 0.05 * f;
    script.hover_s = 10.0;
    script.effects = effects;
    script.effects.thrust_loss_fraction = 0.07;
    airborne.push_back(simulateDynamicFlight(first_seed + f, script));
    script.spans = "hovers";
    hovers.push_back(simulateDynamicFlight(first_seed + f, script));
  }
  const gap::DiagnosisConfig config;
  // As a whole: the simulator's airborne spans against the stretches found in the logs.
  if (as_a_whole) hovers = weighedAsAWhole(airborne, model);
  return {gap::diagnoseGap(model, vehicle, airborne, config), gap::diagnoseGap(model, vehicle, hovers, config)};
}

}  // namespace

TEST(DynamicFlight, SelectsAsFromItsSteadyHovers) {
  const BothWays both = diagnoseBothWays(10, {});
  const gap::Diagnosis& dynamic = both.airborne;
  EXPECT_GT(dynamic.rotor_time_constant_s, 0.0) << dynamic.rotor_lag;
  EXPECT_GE(2 * dynamic.blocks, dynamic.blocks + dynamic.transient_blocks) << dynamic.method;
  EXPECT_GT(dynamic.dynamic_blocks, 0);
  EXPECT_EQ(dynamic.selected, both.hovers.selected);
  EXPECT_TRUE(dynamic.ambiguous.empty() && both.hovers.ambiguous.empty());
  EXPECT_EQ(both.hovers.selected, std::vector<pe::effects::Kind>{pe::effects::Kind::kThrustLoss});
}

TEST(DynamicFlight, NamesTheTranslationalLiftItsHoversCannotSee) {
  // The same flights with the rotors' edgewise flow: the straight legs lift more than the surfaces
  // say. Weighed from take-off to landing the diagnosis names the translational lift beside the
  // thrust loss; on the hovers alone it cannot see it, and names the thrust loss only.
  pe::sim::SimEffects effects;
  effects.translational_lift_strength = 1.0;
  const BothWays both = diagnoseBothWays(20, effects);
  std::vector<pe::effects::Kind> selected = both.airborne.selected;
  std::sort(selected.begin(), selected.end());
  EXPECT_EQ(selected, (std::vector<pe::effects::Kind>{pe::effects::Kind::kThrustLoss,
                                                      pe::effects::Kind::kTranslationalLift}))
      << both.airborne.method;
  EXPECT_TRUE(both.airborne.ambiguous.empty());
  EXPECT_EQ(both.hovers.selected, std::vector<pe::effects::Kind>{pe::effects::Kind::kThrustLoss});
  EXPECT_GE(2 * both.airborne.blocks, both.airborne.blocks + both.airborne.transient_blocks) << both.airborne.method;
}

TEST(DynamicFlight, WeighedAsAWholeTheAirborneStretchFoundSelectsAsTheHandCutSpans) {
  // issue 35: a manifest giving one mass per flight and no segments. The same five flights (a
  // thrust loss, the straight legs' translational lift) weighed over the simulator's airborne spans
  // and over the stretches found in their logs select the same effects.
  pe::sim::SimEffects effects;
  effects.translational_lift_strength = 1.0;
  const BothWays both = diagnoseBothWays(20, effects, true);
  EXPECT_EQ(both.hovers.selected, both.airborne.selected) << both.hovers.method;
  EXPECT_FALSE(both.airborne.selected.empty());
  EXPECT_EQ(both.hovers.ambiguous.empty(), both.airborne.ambiguous.empty());
}

TEST(AirborneStretch, SaysWhyAFlightHasNone) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  pe::FlightStreams streams;
  streams.source = "ground.ulg";
  streams.motors = 4;
  streams.battery.push_back({0.0, 12.0, -1.0});
  for (int i = 0; i < 500; ++i) {
    pe::RcOutFrame frame;
    frame.time_s = 0.02 * i;
    frame.pwm_us.fill(900.0);
    for (int k = 4; k < pe::kMaxMotors; ++k) frame.pwm_us[k] = 0.0;
    streams.rc_out.push_back(frame);
  }
  try {
    gap::airborneSegments(streams, model, {1.3}, {});
    FAIL() << "found a stretch";
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "ground.ulg: no airborne stretch: no motor output above disarmed_pwm_max_us 950 us on every "
                           "motor (never armed)");
  }
  // Armed 6 s at a hover command: shorter than settling, margin and the shortest weighed stretch.
  for (int i = 100; i < 400; ++i) streams.rc_out[i].pwm_us = {1500, 1500, 1500, 1500, 0, 0, 0, 0};
  try {
    gap::airborneSegments(streams, model, {1.3}, {});
    FAIL() << "found a stretch";
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "ground.ulg: no airborne stretch: armed for 6.0 s in all, the longest stretch holding its "
                           "mass 6.0 s: less than the 10.0 s a weighed stretch needs with its settling");
  }
  for (int i = 400; i < 500; ++i) streams.rc_out[i].pwm_us = {1500, 1500, 1500, 1500, 0, 0, 0, 0};
  streams.rc_out.resize(500);
  for (int i = 500; i < 1500; ++i) {
    pe::RcOutFrame frame;
    frame.time_s = 0.02 * i;
    frame.pwm_us = {1500, 1500, 1500, 1500, 0, 0, 0, 0};
    streams.rc_out.push_back(frame);
  }
  const std::vector<pe::ManifestSegment> one = gap::airborneSegments(streams, model, {1.3}, {});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0].start_s, 2.0 + 4.0, 1e-9);
  EXPECT_NEAR(one[0].end_s, 29.98 - 1.0, 1e-9);
  try {
    gap::airborneSegments(streams, model, {1.3, 1.5}, {});
    FAIL() << "two masses for one stretch";
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "ground.ulg: 2 masses for 1 airborne stretches (2.0 s to 30.0 s)");
  }
}

TEST(DynamicFlight, TheSameFlightsLoggedAtAnyRateKeepTheSameBlocksAndSelectAlike) {
  // issue 35: a block's steadiness judged on its command's trend and noise, not on a frame-by-frame
  // range that grows with the frames a noisy command has (real 250 Hz logs kept 1 hover block in 40).
  // The simulator's controller commands smoothly; a real one's command jitters from frame to frame
  // with its sensors' noise: 16 us on each motor here, drawn anew for every frame logged. A
  // frame-by-frame range judged 156 to 164 of these blocks steady from rate to rate (more than 5 % apart).
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  std::vector<int> kept, steady;
  std::vector<std::vector<pe::effects::Kind>> selected;
  for (int rate : {50, 100, 250, 400}) {
    std::vector<pe::Flight> flights;
    for (int f = 0; f < 5; ++f) {
      Script script;
      script.payload_kg = 0.05 * f;
      script.hover_s = 10.0;
      script.rc_out_rate_hz = rate;
      script.effects.thrust_loss_fraction = 0.07;
      flights.push_back(simulateDynamicFlight(10 + f, script));
      std::mt19937 noise(static_cast<unsigned>(rate * 10 + f));
      std::normal_distribution<double> jitter(0.0, 16.0);
      for (pe::RcOutFrame& frame : flights.back().streams.rc_out) {
        for (int k = 0; k < 4; ++k) frame.pwm_us[k] += jitter(noise);
      }
    }
    const gap::Diagnosis diagnosis = gap::diagnoseGap(model, vehicle, flights, gap::DiagnosisConfig{});
    kept.push_back(diagnosis.blocks);
    steady.push_back(diagnosis.blocks - diagnosis.dynamic_blocks);
    selected.push_back(diagnosis.selected);
    std::printf("%d Hz (%zu RCOut messages in the first flight): %d blocks kept (%d dynamic), %d transient; %s\n",
                rate, flights[0].streams.rc_out.size(), diagnosis.blocks, diagnosis.dynamic_blocks,
                diagnosis.transient_blocks, diagnosis.method.c_str());
  }
  for (std::size_t r = 1; r < kept.size(); ++r) {
    EXPECT_NEAR(kept[r], kept[0], 0.05 * kept[0]) << "rate " << r;
    EXPECT_NEAR(steady[r], steady[0], 0.05 * steady[0]) << "rate " << r;
    EXPECT_EQ(selected[r], selected[0]) << "rate " << r;
  }
  EXPECT_EQ(selected[0], std::vector<pe::effects::Kind>{pe::effects::Kind::kThrustLoss});
}

namespace {

// Five flights of kNearTheGroundProfile with the ground's lift at `strength` (1: Cheeseman and
// Bennett's) and a thrust loss of `thrust_loss`, diagnosed with `config`; each world flown once.
gap::Diagnosis diagnoseNearTheGround(double strength, const gap::DiagnosisConfig& config, double thrust_loss = 0.0,
                                     double low_hover_s = 8.0) {
  static std::map<std::tuple<double, double, double>, std::vector<pe::Flight>> flown;
  std::vector<pe::Flight>& flights = flown[{strength, thrust_loss, low_hover_s}];
  for (int f = static_cast<int>(flights.size()); f < 5; ++f) {
    Script script;
    script.profile = kNearTheGroundProfile;
    script.hover_s = 20.0;
    script.low_hover_s = low_hover_s;
    if (strength > 0.0) script.effects.ground_effect_strength = strength;
    if (thrust_loss > 0.0) script.effects.thrust_loss_fraction = thrust_loss;
    flights.push_back(simulateDynamicFlight(40 + f, script));
  }
  return gap::diagnoseGap(pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml")),
                          pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf")), flights, config);
}

// Whether `kind` is named (selected).
bool names(const gap::Diagnosis& diagnosis, pe::effects::Kind kind) {
  return std::find(diagnosis.selected.begin(), diagnosis.selected.end(), kind) != diagnosis.selected.end();
}

// Whether `kind` is named or among an ambiguous round's candidates.
bool namesOrSuggests(const gap::Diagnosis& diagnosis, pe::effects::Kind kind) {
  for (const gap::Ambiguity& ambiguity : diagnosis.ambiguous) {
    if (std::find(ambiguity.kinds.begin(), ambiguity.kinds.end(), kind) != ambiguity.kinds.end()) return true;
  }
  return names(diagnosis, kind);
}

}  // namespace

TEST(DynamicFlight, AGroundEffectIsJudgedWhereItsLawActs) {
  // The ground's lift on a sixth of the blocks moves the held-out error over all of them by less
  // than the model family's mismatch does; on the blocks near the ground it stands clear of it.
  gap::DiagnosisConfig config;
  const gap::Diagnosis judged = diagnoseNearTheGround(1.0, config);
  EXPECT_TRUE(names(judged, pe::effects::Kind::kGroundEffect)) << judged.method;
  const double near_the_ground = config.min_regional_improvement_pct.at(pe::effects::Kind::kGroundEffect);
  config.min_regional_improvement_pct.clear();
  config.min_later_regional_improvement_pct.clear();
  const gap::Diagnosis overall = diagnoseNearTheGround(1.0, config);
  EXPECT_FALSE(namesOrSuggests(overall, pe::effects::Kind::kGroundEffect));
  // Measured 2026-12-06: over all blocks 0.39 -> 0.32 %, on the 50 near the ground 0.58 -> 0.31 %.
  int steps = 0;
  for (const gap::SelectionStep& step : overall.trace) {
    if (step.kind != pe::effects::Kind::kGroundEffect || step.round != 1) continue;
    ++steps;
    EXPECT_LT(step.base_heldout_rmse_pct - step.heldout_rmse_pct, config.min_improvement_pct) << step.verdict;
    EXPECT_GT(step.regional.blocks, 20);
    EXPECT_GT(step.regional.base_pwm_rmse_pct - step.regional.pwm_rmse_pct, near_the_ground) << step.verdict;
  }
  EXPECT_GT(steps, 0);
}

// min_regional_improvement_pct's ground effect (0.140 points, the family's null flights' floor
// near the ground 25 % up) between the ground's lift at half strength, which moves these flights'
// held-out error near the ground by 0.10 points, and at three quarters, 0.18 (measured 2026-12-06):
// halving the threshold names the one, raising it by half leaves the other unnamed.
TEST(DynamicFlight, TheGroundEffectsThresholdLiesBetweenHalfAndThreeQuartersOfItsStrength) {
  gap::DiagnosisConfig config;
  EXPECT_TRUE(names(diagnoseNearTheGround(0.75, config), pe::effects::Kind::kGroundEffect));
  EXPECT_FALSE(namesOrSuggests(diagnoseNearTheGround(0.5, config), pe::effects::Kind::kGroundEffect));
  double& threshold = config.min_regional_improvement_pct.at(pe::effects::Kind::kGroundEffect);
  const double calibrated = threshold;
  threshold = 1.5 * calibrated;
  EXPECT_FALSE(namesOrSuggests(diagnoseNearTheGround(0.75, config), pe::effects::Kind::kGroundEffect));
  threshold = 0.5 * calibrated;
  EXPECT_TRUE(names(diagnoseNearTheGround(0.5, config), pe::effects::Kind::kGroundEffect));
}

// min_later_regional_improvement_pct's ground effect (0.365 points, what an earlier law leaves near
// the ground on the family's development seeds, 25 % up) after a thrust loss of 6 %, the ground's
// lift confined to two 10 s hovers, too little thrust to pass for more than the parts' spread: at
// 1.5 times Cheeseman and Bennett's it lowers the PWM view's held-out error near the ground (the
// only view: no ESC telemetry) by 0.28 points, at 2.1 times by 0.45 (measured 2026-12-06).
// Halving the threshold names the one, raising it by half leaves the other unnamed.
TEST(DynamicFlight, AfterAnEarlierEffectTheGroundEffectsThresholdLiesBetweenTwoStrengths) {
  gap::DiagnosisConfig config;
  const auto afterAThrustLoss = [&config](double strength) {
    const gap::Diagnosis diagnosis = diagnoseNearTheGround(strength, config, 0.06, 10.0);
    EXPECT_TRUE(names(diagnosis, pe::effects::Kind::kThrustLoss)) << strength;
    return diagnosis;
  };
  EXPECT_TRUE(names(afterAThrustLoss(2.1), pe::effects::Kind::kGroundEffect));
  const gap::Diagnosis weak = afterAThrustLoss(1.5);
  EXPECT_FALSE(namesOrSuggests(weak, pe::effects::Kind::kGroundEffect));
  const auto refused = std::find_if(weak.trace.begin(), weak.trace.end(), [](const gap::SelectionStep& step) {
    return step.kind == pe::effects::Kind::kGroundEffect && step.round == 2;
  });
  ASSERT_NE(refused, weak.trace.end());
  EXPECT_NE(refused->verdict.find("not named: after thrust_loss, an effect must move the thrust beyond healthy parts' "
                                  "spread"),
            std::string::npos)
      << refused->verdict;
  EXPECT_NE(refused->verdict.find("fall by more than what an earlier law leaves there (PWM view"), std::string::npos)
      << refused->verdict;
  EXPECT_NE(refused->verdict.find("> 0.365 points needed)"), std::string::npos) << refused->verdict;
  double& threshold = config.min_later_regional_improvement_pct.at(pe::effects::Kind::kGroundEffect);
  const double calibrated = threshold;
  threshold = 1.5 * calibrated;
  EXPECT_FALSE(namesOrSuggests(afterAThrustLoss(2.1), pe::effects::Kind::kGroundEffect));
  threshold = 0.5 * calibrated;
  EXPECT_TRUE(names(afterAThrustLoss(1.5), pe::effects::Kind::kGroundEffect));
}

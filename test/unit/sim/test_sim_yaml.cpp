// Readers of the simulator's files: parameters, effects, flight profiles and manifests. Every
// refusal is one exact line naming the file, the line, the key and the value.
#include <gtest/gtest.h>

#include <filesystem>

#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/physics/sim_effects_yaml.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

template <typename F>
std::string refusal(F parse) {
  try {
    parse();
  } catch (const pe::InputError& e) {
    return e.what();
  }
  return "accepted";
}

const std::string& paramsText() {
  static const std::string text = pe::readTextFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
  return text;
}

std::string paramsRefusal(const std::string& from, const std::string& to) {
  const std::string text = replaced(paramsText(), from, to);
  return refusal([&] { pe::sim::parseSimParamsYaml(text, "p.yaml"); });
}

std::string effectsRefusal(const std::string& text) {
  return refusal([&] { pe::sim::parseSimEffectsYaml(text, "e.yaml"); });
}

// What an effects file reads as: its summary.
std::string effectsRead(const std::string& text) { return pe::sim::parseSimEffectsYaml(text, "e.yaml").summary(); }

// A small valid profile; each test breaks one thing in it.
const std::string kProfile = R"(autopilot:
  flavour: px4
  pwm_min_us: 1100
  pwm_max_us: 1950
  disarmed_pwm_us: 900
  rc_out_rate_hz: 50
vehicle:
  urdf: ../f450_quad.urdf
  centre_of_mass_offset_m: [0, 0, 0]
  landing_gear: {height_m: 0.12, half_width_m: 0.12}
  drag_area_m2: 0.04
  battery_initial_soc: 0.9
payload_cable: {length_m: 1.0, attach_point_m: [0, 0, -0.04], stiffness_n_per_m: 1000, damping_n_s_per_m: 10}
manifest: {settle_s: 5}
segments:
  - {type: wait, duration_s: 2}
  - {type: takeoff, height_m: 2.0, rate_m_s: 1.0}
  - {type: hover, duration_s: 10}
  - {type: land, rate_m_s: 0.5}
  - {type: payload, mass_kg: 0.3, duration_s: 2}
  - {type: takeoff, height_m: 2.0, rate_m_s: 1.0}
  - {type: hover, duration_s: 10}
  - {type: land, rate_m_s: 0.5}
)";

std::string profileRefusal(const std::string& from, const std::string& to) {
  const std::string text = replaced(kProfile, from, to);
  return refusal([&] { pe::sim::parseFlightProfileYaml(text, "config/sim/f.yaml"); });
}

const std::string kManifest = R"(flights:
  - bag: a.bag
    segments:
      - {start: 5, end: 30, mass_kg: 1.315}
      - {start: 40, end: 70.5, mass_kg: 1.609}
)";

std::string manifestRefusal(const std::string& from, const std::string& to) {
  const std::string text = replaced(kManifest, from, to);
  return refusal([&] { pe::parseFlightManifest(text, "m.yaml"); });
}

}  // namespace

TEST(SimParamsYaml, ReadsTheBundledParameterFiles) {
  const pe::sim::SimParams params = pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
  EXPECT_EQ(params.chain.motor.name, "DJI 2212 920KV");
  EXPECT_EQ(params.chain.motor.kv_rpm_per_v, 920.0);
  EXPECT_EQ(params.chain.esc.pwm_zero_us, 1071.0);
  EXPECT_EQ(params.battery.ocv_soc.size(), 13u);
  EXPECT_NEAR(params.bench.sensors.thrust_n.sigma, 0.0098, 1e-12);
  EXPECT_EQ(params.bench.sweep_pwm_max_us, 1900.0);
  const pe::sim::SimParams second = pe::sim::loadSimParamsFile(repoPath("config/sim/430lite_dji2312e_dji9450.yaml"));
  EXPECT_EQ(second.chain.propeller.name, "DJI 9450");
  EXPECT_EQ(second.bench.sweep_pwm_max_us, 1800.0);
}

TEST(SimParamsYaml, RefusesUnknownMissingAndOutOfRangeValues) {
  EXPECT_EQ(paramsRefusal("  kv_rpm_per_v: 920 ", "  kv_rpm_per_v: 920\n  colour: red "),
            "p.yaml:28: motor.colour: unknown key (allowed: name, kv_rpm_per_v, winding_resistance_ohm, "
            "no_load_current_a, reference_temperature_c, flux_temperature_coefficient_per_c, rotor_inertia_kg_m2, "
            "thermal_capacity_j_per_c, thermal_resistance_c_per_w)");
  EXPECT_EQ(paramsRefusal("  kv_rpm_per_v: 920 ", "  # kv removed"), "p.yaml:26: motor.kv_rpm_per_v: missing key");
  EXPECT_EQ(paramsRefusal("  kv_rpm_per_v: 920 ", "  kv_rpm_per_v: -920 "),
            "p.yaml:27: motor.kv_rpm_per_v: -920 is outside 10..10000 rpm/V");
  EXPECT_EQ(paramsRefusal("  pwm_full_us: 1957", "  pwm_full_us: 1200"),
            "p.yaml:21: esc.pwm_full_us: 1200 must be at least 200 us above pwm_zero_us (1071)");
  EXPECT_EQ(paramsRefusal("  thrust_coefficient: 0.0807", "  thrust_coefficient: .nan"),
            "p.yaml:47: propeller.thrust_coefficient: expected a finite number, got '.nan'");
  EXPECT_EQ(paramsRefusal("3.80, 3.84", "3.90, 3.84"),
            "p.yaml:62: battery.open_circuit_voltage.cell_v: must increase with soc (3.84 after 3.9)");
  EXPECT_EQ(paramsRefusal("{sigma_a: 0.106", "{sigma_a: -0.106"),
            "p.yaml:80: bench.sensors.current.sigma_a: -0.106 is outside 0..10");
  EXPECT_EQ(paramsRefusal("  rotor_inertia_kg_m2: 5.0e-6", "  rotor_inertia_kg_m2: 0"),
            "p.yaml:36: motor.rotor_inertia_kg_m2: 0 is outside 0..0.01 kg m^2 (must be positive)");
  EXPECT_EQ(paramsRefusal("  solidity: 0.09", "  solidity: 0.9"),
            "p.yaml:53: propeller.solidity: 0.9 is outside 0.02..0.5");
  // A torque too small for the thrust: figure of merit 1.16, beyond the 1/1.15 = 0.87 kappa allows.
  EXPECT_EQ(paramsRefusal("  torque_coefficient: 0.00445", "  torque_coefficient: 0.0025"),
            "p.yaml:48: propeller.torque_coefficient: 0.0025 is below the induced torque of thrust coefficient "
            "0.0807 (figure of merit 1.16, at most 1/1.15)");
  EXPECT_EQ(paramsRefusal("format_version: 1", "format_version: 2"),
            "p.yaml:15: format_version: 2 is not supported (this reader knows 1)");
}

TEST(SimEffectsYaml, ReadsEveryEffectWithItsParameter) {
  EXPECT_EQ(effectsRead("supply_resistance: {ohm: 0.05}\nair_density: {temperature_c: 35, pressure_pa: 90000}\n"
                        "ground_effect: {strength: 1.0}\nthrust_loss: {fraction: 0.05}\n"
                        "motor_temperature: {thermal_resistance_c_per_w: 2.0}\nclimb_inflow: {strength: 0.5}\n"
                        "esc_offset: {us: -15}\n"),
            "supply_resistance(ohm=0.05) air_density(temperature_c=35,pressure_pa=90000) ground_effect(strength=1) "
            "thrust_loss(fraction=0.05) motor_temperature(thermal_resistance_c_per_w=2) climb_inflow(strength=0.5) "
            "esc_offset(us=-15)");
  EXPECT_EQ(effectsRead("{}"), "none");
}

// The forms of three effects' laws, so that no correction fits its truth exactly.
TEST(SimEffectsYaml, ReadsTheLawsForms) {
  EXPECT_EQ(effectsRead("supply_resistance: {ohm: 0.05, current_coefficient_per_a: 0.01}\n"
                        "thrust_loss: {fraction: 0.05, load_exponent: 0.5, reference_thrust_n: 3.2}\n"
                        "esc_offset: {us: -15, per_esc_us: [2, -3, 1, 0], gain: 1.02, dead_band_us: 4}\n"),
            "supply_resistance(ohm=0.05,current_coefficient_per_a=0.01) "
            "thrust_loss(fraction=0.05,load_exponent=0.5,reference_thrust_n=3.2) "
            "esc_offset(us=-15,per_esc_us=[2;-3;1;0],gain=1.02,dead_band_us=4)");
  EXPECT_EQ(effectsRefusal("thrust_loss: {fraction: 0.05, load_exponent: 0.5}\n"),
            "e.yaml:1: thrust_loss.reference_thrust_n: missing key");
  EXPECT_EQ(effectsRefusal("esc_offset: {us: 20, gain: 1.5}\n"), "e.yaml:1: esc_offset.gain: 1.5 is outside 0.8..1.2");
  EXPECT_EQ(effectsRefusal("esc_offset: {us: 20, dead_band_us: -1}\n"),
            "e.yaml:1: esc_offset.dead_band_us: -1 is outside 0..50 us");
  EXPECT_EQ(effectsRefusal("supply_resistance: {ohm: 0.05, current_coefficient_per_a: 0.5}\n"),
            "e.yaml:1: supply_resistance.current_coefficient_per_a: 0.5 is outside 0..0.1 1/A");
  EXPECT_EQ(effectsRefusal("esc_offset: {us: 20, per_esc_us: [1, x]}\n"),
            "e.yaml:1: esc_offset.per_esc_us: expected a number, got 'x'");
}

TEST(SimEffectsYaml, RefusesUnknownEffectsAndBadParameters) {
  EXPECT_EQ(effectsRefusal("thrust_loss: {fraction: 0.05}\nwind: {speed_m_s: 3}\n"),
            "e.yaml:2: wind: unknown key (allowed: supply_resistance, air_density, ground_effect, thrust_loss, "
            "motor_temperature, climb_inflow, esc_offset, translational_lift)");
  EXPECT_EQ(effectsRefusal("ground_effect: {height_m: 1}\n"),
            "e.yaml:1: ground_effect.height_m: unknown key (allowed: strength)");
  EXPECT_EQ(effectsRefusal("ground_effect:\n"), "e.yaml:1: ground_effect: missing key");
  EXPECT_EQ(effectsRefusal("esc_offset: {us: 20}\nthrust_loss: {fraction: 0.7}\n"),
            "e.yaml:2: thrust_loss.fraction: 0.7 is outside 0..0.5");
  EXPECT_EQ(effectsRefusal("air_density: {temperature_c: 20, pressure_pa: 9000}\n"),
            "e.yaml:1: air_density.pressure_pa: 9000 is outside 50000..110000 Pa");
  EXPECT_EQ(effectsRefusal("climb_inflow: {strength: 3.5}\n"), "e.yaml:1: climb_inflow.strength: 3.5 is outside 0..3");
  EXPECT_EQ(effectsRefusal("climb_inflow: {per_m_s: 0.05}\n"),
            "e.yaml:1: climb_inflow.per_m_s: unknown key (allowed: strength)");
  EXPECT_EQ(effectsRefusal("supply_resistance: {ohm: ten}\n"),
            "e.yaml:1: supply_resistance.ohm: expected a number, got 'ten'");
}

TEST(FlightProfileYaml, ReadsTheBundledProfiles) {
  const pe::sim::FlightProfile profile = pe::sim::loadFlightProfileFile(repoPath("config/sim/default_flight.yaml"));
  EXPECT_EQ(profile.autopilot.flavour, pe::sim::AutopilotFlavour::kPx4);
  EXPECT_EQ(profile.autopilot.rc_out_rate_hz, 50.0);
  EXPECT_EQ(profile.vehicle.urdf_path, repoPath("config/sim/../f450_quad.urdf"));
  const std::vector<pe::sim::ScheduledSegment> schedule = pe::sim::scheduleFlight(profile);
  EXPECT_GT(schedule.back().end_s, 170.0);  // about three minutes
  EXPECT_LT(schedule.back().end_s, 190.0);
  const pe::sim::FlightProfile demo = pe::sim::loadFlightProfileFile(repoPath("config/demo/demo_flight_profile.yaml"));
  EXPECT_EQ(demo.autopilot.rc_out_rate_hz, 20.0);
}

TEST(FlightProfileYaml, SchedulesClimbsByRateAndLandingsWithTouchdownTime) {
  const pe::sim::FlightProfile profile = pe::sim::parseFlightProfileYaml(kProfile, "config/sim/f.yaml");
  const std::vector<pe::sim::ScheduledSegment> schedule = pe::sim::scheduleFlight(profile);
  ASSERT_EQ(schedule.size(), 8u);
  EXPECT_DOUBLE_EQ(schedule[1].start_s, 2.0);
  EXPECT_DOUBLE_EQ(schedule[1].end_s, 2.0 + pe::sim::kTakeoffSpinUpS + (2.0 - 0.12) / 1.0);
  EXPECT_DOUBLE_EQ(schedule[2].end_s - schedule[2].start_s, 10.0);
  EXPECT_DOUBLE_EQ(schedule[3].end_s - schedule[3].start_s, (2.0 - 0.12) / 0.5 + pe::sim::kTouchdownS);
  EXPECT_DOUBLE_EQ(schedule[6].payload_mass_kg, 0.3);
  EXPECT_DOUBLE_EQ(schedule[2].payload_mass_kg, 0.0);
}

TEST(FlightProfileYaml, ManifestSpansAreHoversUnlessAirborneIsAsked) {
  EXPECT_EQ(pe::sim::parseFlightProfileYaml(kProfile, "f.yaml").manifest_spans, pe::sim::ManifestSpans::kHovers);
  const std::string hovers = replaced(kProfile, "{settle_s: 5}", "{settle_s: 5, spans: hovers}");
  EXPECT_EQ(pe::sim::parseFlightProfileYaml(hovers, "f.yaml").manifest_spans, pe::sim::ManifestSpans::kHovers);
  const std::string airborne = replaced(kProfile, "{settle_s: 5}", "{settle_s: 5, spans: airborne}");
  EXPECT_EQ(pe::sim::parseFlightProfileYaml(airborne, "f.yaml").manifest_spans, pe::sim::ManifestSpans::kAirborne);
  EXPECT_EQ(profileRefusal("{settle_s: 5}", "{settle_s: 5, spans: legs}"),
            "config/sim/f.yaml:14: manifest.spans: 'legs' is not one of hovers, airborne");
  EXPECT_EQ(profileRefusal("{settle_s: 5}", "{settle_s: 5, span: airborne}"),
            "config/sim/f.yaml:14: manifest.span: unknown key (allowed: settle_s, spans)");
  // An airborne span must carry its payload from lift-off to touchdown: the payload may not rest
  // on the ground in between, not even in a climb or a descent.
  const std::string second_hover = "mass_kg: 0.3, duration_s: 2}\n  - {type: takeoff, height_m: 2.0, rate_m_s: 1.0}\n"
                                   "  - {type: hover, duration_s: 10}\n";
  const std::string low =
      replaced(airborne, second_hover, second_hover + "  - {type: descend, height_m: 1.0, rate_m_s: 1.0}\n");
  EXPECT_EQ(refusal([&] { pe::sim::parseFlightProfileYaml(low, "config/sim/f.yaml"); }),
            "config/sim/f.yaml:23: segments[7].height_m: descend to 1 m with the 0.3 kg payload on a 1 m cable: the "
            "payload would rest on the ground within an airborne manifest span (stay at 1.24 m or higher)");
  EXPECT_EQ(refusal([&] { pe::sim::parseFlightProfileYaml(replaced(low, "spans: airborne", "spans: hovers"), "f.yaml"); }),
            "accepted");
}

TEST(FlightProfileYaml, ReadsAWeakPropellerFault) {
  EXPECT_FALSE(pe::sim::parseFlightProfileYaml(kProfile, "f.yaml").faults.weak_propeller);
  const std::string faulty = replaced(kProfile, "manifest:", "faults: {weak_propeller: {motor: 3, thrust_factor: 0.85, damage: worn}}\nmanifest:");
  const pe::sim::FlightProfile profile = pe::sim::parseFlightProfileYaml(faulty, "f.yaml");
  ASSERT_TRUE(profile.faults.weak_propeller);
  EXPECT_EQ(profile.faults.weak_propeller->motor, 3);
  EXPECT_EQ(profile.faults.weak_propeller->thrust_factor, 0.85);
  EXPECT_EQ(profile.faults.weak_propeller->damage, pe::sim::PropellerDamage::kWorn);
  const auto faultRefusal = [&](const std::string& from, const std::string& to) {
    const std::string text = replaced(faulty, from, to);
    return refusal([&] { pe::sim::parseFlightProfileYaml(text, "config/sim/f.yaml"); });
  };
  EXPECT_EQ(faultRefusal("thrust_factor: 0.85", "thrust_factor: 1.2"),
            "config/sim/f.yaml:14: faults.weak_propeller.thrust_factor: 1.2 is outside 0.1..1");
  EXPECT_EQ(faultRefusal("motor: 3", "motor: 0"),
            "config/sim/f.yaml:14: faults.weak_propeller.motor: 0 is not a motor (they count from 1)");
  EXPECT_EQ(faultRefusal("motor: 3", "motor: three"),
            "config/sim/f.yaml:14: faults.weak_propeller.motor: expected a number, got 'three'");
  EXPECT_EQ(faultRefusal("damage: worn", "damage: bent"),
            "config/sim/f.yaml:14: faults.weak_propeller.damage: 'bent' is not one of chipped, worn");
  EXPECT_EQ(faultRefusal(", damage: worn", ""), "config/sim/f.yaml:14: faults.weak_propeller.damage: missing key");
  EXPECT_EQ(faultRefusal("weak_propeller:", "bent_arm:"),
            "config/sim/f.yaml:14: faults.bent_arm: unknown key (allowed: weak_propeller)");
}

TEST(FlightProfileYaml, ReadsTheVehiclesParts) {
  EXPECT_FALSE(pe::sim::parseFlightProfileYaml(kProfile, "f.yaml").vehicle.parts);
  const std::string parted = replaced(kProfile, "  battery_initial_soc: 0.9\n",
                                      "  battery_initial_soc: 0.9\n  parts: {seed: 7, thrust_coefficient_spread: 0.03, "
                                      "torque_coefficient_spread: 0.025, kv_spread: 0.02, esc_end_point_spread_us: 8, "
                                      "spin_torque_ratio: 1.06}\n");
  const pe::sim::FlightProfile profile = pe::sim::parseFlightProfileYaml(parted, "f.yaml");
  ASSERT_TRUE(profile.vehicle.parts);
  EXPECT_EQ(profile.vehicle.parts->seed, 7u);
  EXPECT_EQ(profile.vehicle.parts->thrust_coefficient_spread, 0.03);
  EXPECT_EQ(profile.vehicle.parts->torque_coefficient_spread, 0.025);
  EXPECT_EQ(profile.vehicle.parts->kv_spread, 0.02);
  EXPECT_EQ(profile.vehicle.parts->esc_end_point_spread_us, 8.0);
  EXPECT_EQ(profile.vehicle.parts->spin_torque_ratio, 1.06);
  const auto partsRefusal = [&](const std::string& from, const std::string& to) {
    const std::string text = replaced(parted, from, to);
    return refusal([&] { pe::sim::parseFlightProfileYaml(text, "config/sim/f.yaml"); });
  };
  EXPECT_EQ(partsRefusal("kv_spread: 0.02", "kv_spread: 0.5"),
            "config/sim/f.yaml:13: vehicle.parts.kv_spread: 0.5 is outside 0..0.1");
  EXPECT_EQ(partsRefusal("thrust_coefficient_spread: 0.03", "thrust_coefficient_spread: -0.03"),
            "config/sim/f.yaml:13: vehicle.parts.thrust_coefficient_spread: -0.03 is outside 0..0.1");
  EXPECT_EQ(partsRefusal("torque_coefficient_spread: 0.025", "torque_coefficient_spread: .nan"),
            "config/sim/f.yaml:13: vehicle.parts.torque_coefficient_spread: expected a finite number, got '.nan'");
  EXPECT_EQ(partsRefusal("esc_end_point_spread_us: 8", "esc_end_point_spread_us: 80"),
            "config/sim/f.yaml:13: vehicle.parts.esc_end_point_spread_us: 80 is outside 0..30 us");
  EXPECT_EQ(partsRefusal("spin_torque_ratio: 1.06", "spin_torque_ratio: 1.5"),
            "config/sim/f.yaml:13: vehicle.parts.spin_torque_ratio: 1.5 is outside 0.8..1.25");
  EXPECT_EQ(partsRefusal("seed: 7", "seed: -7"), "config/sim/f.yaml:13: vehicle.parts.seed: -7 is outside 0..1000000000");
  EXPECT_EQ(partsRefusal("seed: 7", "seed: 7.5"), "config/sim/f.yaml:13: vehicle.parts.seed: expected an integer, got '7.5'");
  // A vehicle's parts are its calibration: every key is required.
  EXPECT_EQ(partsRefusal(", spin_torque_ratio: 1.06", ""), "config/sim/f.yaml:13: vehicle.parts.spin_torque_ratio: missing key");
  EXPECT_EQ(partsRefusal("kv_spread:", "kv_sigma:"),
            "config/sim/f.yaml:13: vehicle.parts.kv_sigma: unknown key (allowed: seed, thrust_coefficient_spread, "
            "torque_coefficient_spread, kv_spread, esc_end_point_spread_us, spin_torque_ratio)");
}

TEST(FlightProfileYaml, RefusesImpossibleSegments) {
  EXPECT_EQ(profileRefusal("  - {type: hover, duration_s: 10}\n  - {type: land",
                           "  - {type: takeoff, height_m: 3, rate_m_s: 1}\n  - {type: land"),
            "config/sim/f.yaml:18: segments[2].type: takeoff while flying at 2 m (land first)");
  EXPECT_EQ(profileRefusal("  - {type: wait, duration_s: 2}", "  - {type: hover, duration_s: 2}"),
            "config/sim/f.yaml:16: segments[0].type: hover on the ground (take off first)");
  EXPECT_EQ(profileRefusal("  - {type: hover, duration_s: 10}\n  - {type: land",
                           "  - {type: climb, height_m: 1.5, rate_m_s: 1}\n  - {type: land"),
            "config/sim/f.yaml:18: segments[2].height_m: climb to 1.5 m from 2 m (use descend)");
  EXPECT_EQ(profileRefusal("  - {type: hover, duration_s: 10}\n  - {type: land",
                           "  - {type: descend, height_m: 2.5, rate_m_s: 1}\n  - {type: land"),
            "config/sim/f.yaml:18: segments[2].height_m: descend to 2.5 m from 2 m (use climb)");
  EXPECT_EQ(profileRefusal("  - {type: hover, duration_s: 10}\n  - {type: land",
                           "  - {type: payload, mass_kg: 0.3, duration_s: 1}\n  - {type: land"),
            "config/sim/f.yaml:18: segments[2].type: payload while flying at 2 m (land first)");
  EXPECT_EQ(profileRefusal("0.3, duration_s: 2}\n  - {type: takeoff, height_m: 2.0,",
                           "0.3, duration_s: 2}\n  - {type: takeoff, height_m: 1.0,"),
            "config/sim/f.yaml:22: segments[6].type: hover at 1 m with the 0.3 kg payload on a 1 m cable: the "
            "payload would rest on the ground (hover at 1.24 m or higher)");
  EXPECT_EQ(profileRefusal("  - {type: wait, duration_s: 2}", "  - {type: move, east_m: 5, north_m: 0, speed_m_s: 2}"),
            "config/sim/f.yaml:16: segments[0].type: move on the ground (take off first)");
  EXPECT_EQ(profileRefusal("  - {type: hover, duration_s: 10}\n  - {type: land",
                           "  - {type: move, east_m: 5, north_m: 0, speed_m_s: 20}\n  - {type: land"),
            "config/sim/f.yaml:18: segments[2].speed_m_s: 20 is outside 0.2..12 m/s");
  EXPECT_EQ(profileRefusal("  - {type: hover, duration_s: 10}\n  - {type: land",
                           "  - {type: move, east_m: 0, north_m: 0, speed_m_s: 2}\n  - {type: land"),
            "config/sim/f.yaml:18: segments[2].east_m: a move of 0 m (0.1 to 2000 m)");
  const std::string ends_flying = kProfile.substr(0, kProfile.rfind("  - {type: land"));
  EXPECT_EQ(refusal([&] { pe::sim::parseFlightProfileYaml(ends_flying, "config/sim/f.yaml"); }),
            "config/sim/f.yaml:16: segments: the profile ends in flight (add a land segment)");
}

TEST(FlightProfileYaml, RefusesBadValuesAndUnknownKeys) {
  EXPECT_EQ(profileRefusal("  rc_out_rate_hz: 50", "  rc_out_rate_hz: 600"),
            "config/sim/f.yaml:6: autopilot.rc_out_rate_hz: 600 is outside 10..500 Hz");
  EXPECT_EQ(profileRefusal("  rc_out_rate_hz: 50\n", ""), "config/sim/f.yaml:2: autopilot.rc_out_rate_hz: missing key");
  EXPECT_EQ(profileRefusal("  disarmed_pwm_us: 900", "  disarmed_pwm_us: 1200"),
            "config/sim/f.yaml:5: autopilot.disarmed_pwm_us: 1200 is outside 500..1100 us (or 0)");
  EXPECT_EQ(profileRefusal("flavour: px4", "flavour: betaflight"),
            "config/sim/f.yaml:2: autopilot.flavour: 'betaflight' is not one of px4, ardupilot");
  EXPECT_EQ(
      profileRefusal("{type: wait, duration_s: 2}", "{type: loiter, duration_s: 2}"),
      "config/sim/f.yaml:16: segments[0].type: 'loiter' is not one of wait, takeoff, hover, climb, descend, land, "
      "payload, move");
  EXPECT_EQ(profileRefusal("{type: wait, duration_s: 2}", "{type: wait, duration_s: 2, height_m: 3}"),
            "config/sim/f.yaml:16: segments[0].height_m: unknown key (allowed: type, duration_s)");
  EXPECT_EQ(profileRefusal("{type: hover, duration_s: 10}", "{type: hover, duration_s: -10}"),
            "config/sim/f.yaml:18: segments[2].duration_s: -10 is outside 0..3600 s (must be positive)");
  EXPECT_EQ(profileRefusal("{type: payload, mass_kg: 0.3,", "{type: payload, mass_kg: 7,"),
            "config/sim/f.yaml:20: segments[4].mass_kg: 7 is outside 0.01..5 kg (or 0 for none)");
  EXPECT_EQ(profileRefusal("{type: payload, mass_kg: 0.3,", "{type: payload, mass_kg: 0.005,"),
            "config/sim/f.yaml:20: segments[4].mass_kg: 0.005 is outside 0.01..5 kg (or 0 for none)");
  EXPECT_EQ(profileRefusal("{type: takeoff, height_m: 2.0,", "{type: takeoff, height_m: 0.1,"),
            "config/sim/f.yaml:17: segments[1].height_m: 0.1 is outside 0.17..100 m");
  EXPECT_EQ(
      profileRefusal("{type: takeoff, height_m: 2.0, rate_m_s: 1.0}", "{type: takeoff, height_m: 2.0, rate_m_s: 0.01}"),
      "config/sim/f.yaml:17: segments[1].rate_m_s: 0.01 is outside 0.05..5 m/s");
  EXPECT_EQ(profileRefusal("  - {type: land, rate_m_s: 0.5}", "  - {type: land, rate_m_s: 0}"),
            "config/sim/f.yaml:19: segments[3].rate_m_s: 0 is outside 0.05..5 m/s");
  EXPECT_EQ(profileRefusal("landing_gear: {height_m: 0.12,", "landing_gear: {height_m: 0,"),
            "config/sim/f.yaml:10: vehicle.landing_gear.height_m: 0 is outside 0..1 m (must be positive)");
  EXPECT_EQ(profileRefusal("centre_of_mass_offset_m: [0, 0, 0]", "centre_of_mass_offset_m: [0, 0]"),
            "config/sim/f.yaml:9: vehicle.centre_of_mass_offset_m: expected [x, y, z], got 2 numbers");
}

TEST(FlightManifest, RoundTripsThroughItsWriter) {
  pe::FlightManifest manifest;
  manifest.flights.push_back({"flight_01.bag", {{5.0, 178.0, 1.315}, {180.25, 200.125, 1.711}}, {}});
  manifest.flights.push_back({"/data/flight_02.bag", {{0.1, 0.3, 0.2}}, {}});
  const std::string text = pe::flightManifestToYaml(manifest, "written by a test");
  EXPECT_EQ(text.rfind("# written by a test\n", 0), 0u) << text;
  const pe::FlightManifest read = pe::parseFlightManifest(text, "m.yaml");
  ASSERT_EQ(read.flights.size(), 2u);
  for (std::size_t f = 0; f < 2; ++f) {
    EXPECT_EQ(read.flights[f].log, manifest.flights[f].log);
    ASSERT_EQ(read.flights[f].segments.size(), manifest.flights[f].segments.size());
    for (std::size_t s = 0; s < read.flights[f].segments.size(); ++s) {
      EXPECT_EQ(read.flights[f].segments[s].start_s, manifest.flights[f].segments[s].start_s);
      EXPECT_EQ(read.flights[f].segments[s].end_s, manifest.flights[f].segments[s].end_s);
      EXPECT_EQ(read.flights[f].segments[s].mass_kg, manifest.flights[f].segments[s].mass_kg);
    }
  }
  EXPECT_EQ(refusal([&] { pe::saveFlightManifest(manifest, "/nonexistent/folder/m.yaml", ""); }),
            "/nonexistent/folder/m.yaml: cannot open for writing");
  EXPECT_EQ(pe::resolveLogPath("/x/y/m.yaml", "flight_01.bag"), "/x/y/flight_01.bag");
  EXPECT_EQ(pe::resolveLogPath("/x/y/m.yaml", "/data/flight_02.bag"), "/data/flight_02.bag");
}

TEST(FlightManifest, ReadsTheIssuesExample) {
  const pe::FlightManifest manifest = pe::parseFlightManifest(
      "flights:\n  - bag: flight_01.bag        # path relative to the manifest\n    segments:                 # times "
      "in "
      "seconds from the bag's first message\n      - {start: 5.0, end: 178.0, mass_kg: 1.315}\n",
      "m.yaml");
  ASSERT_EQ(manifest.flights.size(), 1u);
  EXPECT_EQ(manifest.flights[0].segments[0].end_s, 178.0);
}

// The field is `log:` (a rosbag or any format diagnose_gap reads); `bag:`, its old name, still reads.
TEST(FlightManifest, ReadsLogAndTheOldBag) {
  const std::string segments = "    segments:\n      - {start: 1, end: 2, mass_kg: 1.3}\n";
  const pe::FlightManifest read =
      pe::parseFlightManifest("flights:\n  - log: a.ulg\n" + segments + "  - bag: b.bag\n" + segments, "m.yaml");
  ASSERT_EQ(read.flights.size(), 2u);
  EXPECT_EQ(read.flights[0].log, "a.ulg");
  EXPECT_EQ(read.flights[1].log, "b.bag");
  // The writer writes the new name.
  EXPECT_NE(pe::flightManifestToYaml(read).find("  - log: b.bag\n"), std::string::npos);
  EXPECT_EQ(refusal([&] { pe::parseFlightManifest("flights:\n  - log: a.ulg\n    bag: a.bag\n" + segments, "m.yaml"); }),
            "m.yaml:3: flights[0].bag: give log or bag (its old name), not both");
  EXPECT_EQ(refusal([&] { pe::parseFlightManifest("flights:\n  - segments:\n      - {start: 1, end: 2, mass_kg: 1}\n",
                                                  "m.yaml"); }),
            "m.yaml:2: flights[0].log: missing key");
  EXPECT_EQ(refusal([&] { pe::parseFlightManifest("flights:\n  - log: ''\n" + segments, "m.yaml"); }),
            "m.yaml:2: flights[0].log: is empty");
}

TEST(FlightManifest, RefusesBadSegments) {
  EXPECT_EQ(manifestRefusal("{start: 40, end: 70.5,", "{start: 40, end: 40,"),
            "m.yaml:5: flights[0].segments[1].end: 40 is not after start 40");
  EXPECT_EQ(manifestRefusal("{start: 40, end: 70.5,", "{start: 20, end: 70.5,"),
            "m.yaml:5: flights[0].segments[1].start: 20 is before the previous segment's end 30");
  EXPECT_EQ(manifestRefusal("mass_kg: 1.315}", "mass_kg: 0}"),
            "m.yaml:4: flights[0].segments[0].mass_kg: 0 is outside 0..100 kg (must be positive)");
  EXPECT_EQ(manifestRefusal("mass_kg: 1.315}", "mass_kg: 1.315, weight_g: 1315}"),
            "m.yaml:4: flights[0].segments[0].weight_g: unknown key (allowed: start, end, mass_kg)");
  EXPECT_EQ(manifestRefusal("  - bag: a.bag\n", "  - file: a.bag\n"),
            "m.yaml:2: flights[0].file: unknown key (allowed: log, bag, segments, mass_kg)");
  EXPECT_EQ(refusal([] { pe::parseFlightManifest("flights: []\n", "m.yaml"); }), "m.yaml:1: flights: no flights");
}

TEST(FlightManifest, EntriesKeepAFlightsRefusalAndTheOtherFlights) {
  const std::string path = (std::filesystem::temp_directory_path() / "pe_manifest_entries.yaml").string();
  pe::writeTextFile(path, kManifest + "  - bag: b.bag\n    segments:\n      - {start: 1, end: 2, mass_kg: 0}\n" +
                              "  - bag: c.bag\n    segments:\n      - {start: 3, end: 4, mass_kg: 1.5}\n");
  const std::vector<pe::ManifestEntry> entries = pe::loadFlightManifestEntries(path);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].refusal, "");
  EXPECT_EQ(entries[0].flight.segments.size(), 2u);
  EXPECT_EQ(entries[1].flight.log, "b.bag");
  EXPECT_EQ(entries[1].refusal,
            path + ":8: flights[1].segments[0].mass_kg: 0 is outside 0..100 kg (must be positive)");
  EXPECT_EQ(entries[2].refusal, "");
  EXPECT_EQ(entries[2].flight.segments[0].mass_kg, 1.5);
  // Two flights refused: each on its own line (locating the first once rewrote the document, and
  // the second was then named on the first flight's line).
  pe::writeTextFile(path, kManifest + "  - bag: b.bag\n    segments:\n      - {start: 1, end: 2, mass_kg: 0}\n" +
                              "  - bag: c.bag\n    segments:\n      - {start: 3, end: 4, mass_kg: 1500}\n");
  const std::vector<pe::ManifestEntry> two = pe::loadFlightManifestEntries(path);
  ASSERT_EQ(two.size(), 3u);
  EXPECT_EQ(two[1].refusal, path + ":8: flights[1].segments[0].mass_kg: 0 is outside 0..100 kg (must be positive)");
  EXPECT_EQ(two[2].refusal, path + ":11: flights[2].segments[0].mass_kg: 1500 is outside 0..100 kg (must be positive)");
  // What is wrong with the file itself still refuses it.
  pe::writeTextFile(path, "flights: []\n");
  EXPECT_EQ(refusal([&] { pe::loadFlightManifestEntries(path); }), path + ":1: flights: no flights");
  pe::writeTextFile(path, replaced(kManifest, "  - bag: a.bag\n", "  - file: a.bag\n"));
  EXPECT_EQ(refusal([&] { pe::loadFlightManifestEntries(path); }),
            path + ":2: flights[0].file: unknown key (allowed: log, bag, segments, mass_kg)");
  std::filesystem::remove(path);
}

// A flight weighed as a whole: `mass_kg:` for its airborne stretches instead of segments.
TEST(FlightManifest, ReadsAndWritesAWholeFlightsMass) {
  const pe::FlightManifest read = pe::parseFlightManifest(
      "flights:\n  - log: a.ulg\n    mass_kg: 1.315\n  - log: b.ulg\n    mass_kg: [1.315, 1.52]\n", "m.yaml");
  ASSERT_EQ(read.flights.size(), 2u);
  EXPECT_TRUE(read.flights[0].segments.empty());
  EXPECT_EQ(read.flights[0].airborne_mass_kg, std::vector<double>{1.315});
  EXPECT_EQ(read.flights[1].airborne_mass_kg, (std::vector<double>{1.315, 1.52}));
  const std::string text = pe::flightManifestToYaml(read);
  EXPECT_NE(text.find("mass_kg: 1.315\n"), std::string::npos) << text;
  EXPECT_NE(text.find("mass_kg: [1.315, 1.52]"), std::string::npos) << text;
  EXPECT_EQ(pe::parseFlightManifest(text, "again.yaml").flights[1].airborne_mass_kg, read.flights[1].airborne_mass_kg);
  EXPECT_EQ(refusal([] {
              pe::parseFlightManifest("flights:\n  - log: a.ulg\n    mass_kg: 1.3\n    segments:\n"
                                      "      - {start: 1, end: 2, mass_kg: 1.3}\n", "m.yaml");
            }),
            "m.yaml:3: flights[0].mass_kg: give segments or the flight's mass_kg, not both");
  EXPECT_EQ(refusal([] { pe::parseFlightManifest("flights:\n  - log: a.ulg\n", "m.yaml"); }),
            "m.yaml:2: flights[0].segments: no segments (or mass_kg for the whole airborne stretch)");
  EXPECT_EQ(refusal([] { pe::parseFlightManifest("flights:\n  - log: a.ulg\n    mass_kg: [1.3, 0]\n", "m.yaml"); }),
            "m.yaml:3: flights[0].mass_kg[1]: 0 is outside 0..100 kg (must be positive)");
}

// A log given as a pattern is a flight per matching file; a pattern matching nothing is refused.
TEST(FlightManifest, EntriesExpandALogPattern) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "pe_manifest_glob";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "logs");
  for (const char* name : {"b.ulg", "a.ulg", "c.bin"}) pe::writeTextFile((dir / "logs" / name).string(), "x");
  const std::string path = (dir / "m.yaml").string();
  pe::writeTextFile(path, "flights:\n  - log: logs/*.ulg\n    mass_kg: 1.3\n  - log: none/*.ulg\n    mass_kg: 1.3\n");
  const std::vector<pe::ManifestEntry> entries = pe::loadFlightManifestEntries(path);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].flight.log, (dir / "logs/a.ulg").string());
  EXPECT_EQ(entries[1].flight.log, (dir / "logs/b.ulg").string());
  EXPECT_EQ(entries[1].flight.airborne_mass_kg, std::vector<double>{1.3});
  EXPECT_EQ(entries[2].refusal, path + ":4: flights[1].log: none/*.ulg matches no file");
  std::filesystem::remove_all(dir);
}

// The capability answers on simulated flights, the core estimator fed as the node feeds it: the
// hover endurance predicted 20 s and 60 s after take-off against the time the simulated vehicle,
// hovering on, takes to reach the loaded cut-off, with packs drawn from the battery family (not our
// curve; the estimator is given only cells, rated capacity and cut-off); the payload limit against
// the simulated propulsion's thrust at the top PWM with the pack sagging; a weak propeller flagged,
// a centre-of-gravity offset not.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "propulsion_estimator/common/simulation_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/onboard/capability.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/estimation/motor_change.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/fitting/surface_fit.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/battery_family.h"
#include "propulsion_estimator/sim/physics/propulsion_chain.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/sim/stand/bench_simulator.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

constexpr double kCellCutoffV = 3.5;

// The thesis quad's model; `effects` an effects: section for it (YAML), or none.
pe::PropulsionModel thesisModel(const std::string& effects = "") {
  return pe::parseModelYaml(pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml")) + effects, "thesis model");
}

pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

// Take-off to 2 m and a hover of `hover_s` with `payload_kg` on a 0.3 m cable, from
// `initial_soc`, the centre of gravity `cg_offset` off the URDF's; `faults` a profile section.
std::string profile(double payload_kg, double hover_s, double initial_soc, const std::string& cg_offset = "[0.0, 0.0, 0.0]",
                    const std::string& faults = "") {
  std::string text = "autopilot: {flavour: px4, pwm_min_us: 1100, pwm_max_us: 1950, disarmed_pwm_us: 900, "
                     "rc_out_rate_hz: 50}\n"
                     "vehicle: {urdf: " +
                     repoPath("config/f450_quad.urdf") + ", centre_of_mass_offset_m: " + cg_offset +
                     ", landing_gear: {height_m: 0.12, half_width_m: 0.12}, drag_area_m2: 0.04, "
                     "battery_initial_soc: " +
                     std::to_string(initial_soc) +
                     "}\n"
                     "payload_cable: {length_m: 0.3, attach_point_m: [0.0, 0.0, -0.04], stiffness_n_per_m: 1000, "
                     "damping_n_s_per_m: 10}\n"
                     "manifest: {settle_s: 4}\n" +
                     faults +
                     "segments:\n"
                     "  - {type: wait, duration_s: 2}\n";
  if (payload_kg > 0.0) text += "  - {type: payload, mass_kg: " + std::to_string(payload_kg) + ", duration_s: 2}\n";
  text += "  - {type: takeoff, height_m: 2.0, rate_m_s: 1.0}\n"
          "  - {type: hover, duration_s: " +
          std::to_string(hover_s) +
          "}\n"
          "  - {type: land, rate_m_s: 0.6}\n"
          "  - {type: wait, duration_s: 2}\n";
  return text;
}

// Feeds each message of the simulated flight to the core estimator as the node does, the motor
// health after each accepted RCOut, and evaluates the capability once a second; keeps the
// predictions `predict_after_s` after take-off (the first accepted motor output).
class CapabilitySink : public pe::sim::FlightSink {
 public:
  CapabilitySink(const pe::Vehicle& vehicle, const pe::CapabilityConfig& config, pe::PropulsionModel model = thesisModel(),
                 std::vector<double> predict_after_s = {}, std::optional<pe::MotorReference> reference = std::nullopt)
      : model_(std::move(model)),
        estimator_(model_, vehicle, {}),
        health_(vehicle, {1, 2, 3, 4}, config.motor_health, std::move(reference)),
        capability_(estimator_.model(), 4, config),
        cutoff_v_(*config.cells * config.cell_cutoff_v),
        predict_after_s_(std::move(predict_after_s)),
        predictions(predict_after_s_.size()) {}

  void rcOut(const pe::sim::RcOutSample& s) override {
    if (estimator_.addMotorOutputs(s.time_s, s.time_s, s.channels.data(), s.channels.size()) != pe::Rejection::kNone) {
      return;
    }
    if (!takeoff_s) takeoff_s = s.time_s;
    const pe::EstimatorOutput& out = estimator_.output();
    health_.add(out);
    if (out.hover.hovering && !hover_start_s) hover_start_s = s.time_s;
    if (out.hover.hovering) {
      for (std::size_t k = 0; k < hover_thrust_n.size(); ++k) hover_thrust_n[k] += out.motors[k].estimate.thrust_n;
      ++hover_samples;
    }
    if (s.time_s < next_evaluation_s_) return;
    next_evaluation_s_ = s.time_s + 1.0;
    const pe::MotorHealthVerdict verdict = health_.verdict();
    if (verdict.judged) last_health = verdict;
    if (verdict.flagged_channel != 0) {
      if (!first_flag_s) first_flag_s = s.time_s;
      flagged_channels |= 1u << verdict.flagged_channel;
    }
    // The first hover's figures: once the payload estimate averages a whole window.
    if (!prediction && out.payload.state == pe::PayloadState::kHovering && out.payload.window_s >= 9.5) {
      prediction = capability_.evaluate(out, estimator_.effectSignals(s.time_s));
      prediction_s = s.time_s;
      prediction_truth = truth_;
    }
    for (std::size_t k = 0; k < predict_after_s_.size(); ++k) {
      if (predictions[k] || s.time_s < *takeoff_s + predict_after_s_[k]) continue;
      predictions[k] = Prediction{capability_.evaluate(out, estimator_.effectSignals(s.time_s)), s.time_s,
                                  truth_.battery_current_a};
    }
  }
  void battery(const pe::sim::BatterySample& s) override {
    estimator_.addBattery(s.time_s, s.voltage_v);
    estimator_.addBatteryCurrent(s.time_s, s.current_a);
    // The simulated percentage is the true state of charge: the default mode (ignore) never reads it.
    const double modelled_a = estimator_.output().totals.current_a;
    capability_.addBattery(s.time_s, s.voltage_v, pe::BatteryReport{s.percentage, s.current_a}, modelled_a);
  }
  void imu(const pe::sim::ImuSample& s) override {
    estimator_.addImu(s.time_s, s.orientation, s.linear_acceleration_m_s2);
  }
  void velocity(const pe::sim::VelocitySample& s) override { estimator_.addVerticalSpeed(s.time_s, s.linear_m_s.z()); }
  void pose(const pe::sim::PoseSample&) override {}
  void staticPressure(const pe::sim::ScalarSample&) override {}
  void airTemperature(const pe::sim::ScalarSample&) override {}
  void rangefinder(const pe::sim::RangeSample&) override {}
  void motorTemperature(const pe::sim::ScalarSample&) override {}
  // The cut-off as an autopilot's filtered voltage sees it: the terminal voltage over about a second
  // below the cut-off in hover (not the dip of the take-off's full throttle).
  void truth(const pe::sim::TruthSample& s) override {
    const double dt_s = s.time_s - truth_.time_s;
    truth_ = s;
    filtered_v_ = std::isnan(filtered_v_) ? s.battery_voltage_v
                                          : filtered_v_ + std::min(1.0, dt_s / 1.0) * (s.battery_voltage_v - filtered_v_);
    if (takeoff_s && s.time_s > *takeoff_s + 5.0 && !cutoff_s && filtered_v_ < cutoff_v_) cutoff_s = s.time_s;
  }

  std::optional<double> takeoff_s, hover_start_s, first_flag_s, cutoff_s;
  unsigned flagged_channels = 0;
  std::optional<pe::MotorHealthVerdict> last_health;
  pe::HoverThrusts hover_thrust_n = pe::HoverThrusts(4, 0.0);  ///< summed over the hover's accepted RCOuts
  int hover_samples = 0;
  std::optional<pe::CapabilityReport> prediction;
  double prediction_s = 0.0;
  pe::sim::TruthSample prediction_truth;

 private:
  pe::PropulsionModel model_;
  pe::Estimator estimator_;
  pe::MotorHealth health_;
  pe::CapabilityEstimator capability_;
  double cutoff_v_;
  std::vector<double> predict_after_s_;
  double next_evaluation_s_ = 0.0;
  pe::sim::TruthSample truth_;
  double filtered_v_ = pe::kNaN;

 public:
  // The capability at one of predict_after_s, when it was made and the battery current then.
  struct Prediction {
    pe::CapabilityReport report;
    double made_s;
    double truth_current_a;
  };
  std::vector<std::optional<Prediction>> predictions;
};

// What the user of the thesis quad's pack gives: cells, rated capacity, the cut-off.
pe::CapabilityConfig userPack(int cells = 3, double capacity_ah = 4.0) {
  pe::CapabilityConfig config;
  config.capacity_ah = capacity_ah;
  config.cells = cells;
  config.cell_cutoff_v = kCellCutoffV;
  return config;
}

// Flies `text`; a flight that outlasts its battery ends there (the endurance flights hover on
// until it is empty).
void fly(const std::string& text, CapabilitySink* sink, pe::sim::SimEffects effects = {},
         const pe::sim::SimParams& params = thesisParams(), unsigned seed = 11) {
  const pe::sim::FlightProfile flight = pe::sim::parseFlightProfileYaml(text, "capability_flight.yaml");
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(flight.vehicle.urdf_path);
  try {
    pe::sim::simulateFlight(params, effects, flight, vehicle, seed, sink);
  } catch (const pe::SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("the battery is empty"), std::string::npos) << e.what();
  }
}

pe::Vehicle f450() { return pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf")); }

// Hovers to the loaded cut-off from 100, 60 and 30 % with packs drawn from the battery family
// (each seed a pack of its own: shape, resistances, temperature, age), empty and with 0.3 kg: the
// hover time left predicted 20 s and 60 s after take-off against the time the vehicle took.
// The seeds are below (development, held-out, fresh). With `own_curve` the user also gives the
// pack's own open-circuit curve (capability/battery/ocv_table: the drawn pack's table); `family`
// is the battery family.
void expectEnduranceOnFamilyPacks(const std::vector<std::uint32_t>& seeds, double median_bound = 0.35,
                                  bool own_curve = false, const pe::sim::BatteryFamily& family = {}) {
  std::array<int, 2> cases{}, within_bar{}, within_sigma{}, within_2sigma{};
  std::array<std::vector<double>, 2> errors;
  for (std::uint32_t seed : seeds) {
    const pe::sim::DrawnBattery drawn = pe::sim::drawBattery(family, seed);
    pe::sim::SimParams params = thesisParams();
    params.battery = drawn.params;
    for (double initial_soc : {1.0, 0.6, 0.3}) {
      const double payload_kg = seed % 2 ? 0.0 : 0.3;
      pe::CapabilityConfig user = userPack();
      if (own_curve) {
        user.ocv_table_soc = drawn.params.ocv_soc;
        user.ocv_table_cell_v = drawn.params.ocv_cell_v;
      }
      CapabilitySink sink(f450(), user, thesisModel(), {20.0, 60.0});
      fly(profile(payload_kg, 3000.0, initial_soc), &sink, {}, params);
      ASSERT_TRUE(sink.cutoff_s.has_value()) << drawn.describe();
      if (*sink.cutoff_s < *sink.takeoff_s + 90.0) {
        // Too short to judge a prediction made 60 s after take-off (fresh seed 202 from 30 %).
        std::printf("seed %3u %s, payload %.1f kg, from %3.0f %%: the cut-off %.0f s after take-off, not judged\n",
                    seed, drawn.describe().c_str(), payload_kg, 100.0 * initial_soc, *sink.cutoff_s - *sink.takeoff_s);
        continue;
      }
      for (std::size_t k = 0; k < 2; ++k) {
        const double after_s = k == 0 ? 20.0 : 60.0, bound = k == 0 ? 0.15 : 0.10;
        ASSERT_TRUE(sink.predictions[k].has_value());
        const pe::CapabilityReport& c = sink.predictions[k]->report;
        const double flown_s = *sink.cutoff_s - sink.predictions[k]->made_s;
        const double error = (c.hover_endurance_s - flown_s) / flown_s;
        std::printf("seed %3u %s, payload %.1f kg, from %3.0f %%, after %2.0f s: predicted %4.0f +- %3.0f s, "
                    "flew %4.0f s, error %+5.1f %% (soc %.2f +- %.2f, R %.1f +- %.1f mOhm, hover %.1f A, drawn %.1f A)\n",
                    seed, drawn.describe().c_str(), payload_kg, 100.0 * initial_soc, after_s, c.hover_endurance_s,
                    c.hover_endurance_std_s, flown_s, 100.0 * error, c.state_of_charge, c.state_of_charge_std,
                    1000.0 * c.internal_resistance_ohm, 1000.0 * c.internal_resistance_std_ohm, c.hover_current_a,
                    sink.predictions[k]->truth_current_a);
        EXPECT_FALSE(std::isnan(c.hover_endurance_s)) << "seed " << seed << ": " << c.endurance_basis;
        ++cases[k];
        within_bar[k] += std::abs(error) < bound;
        within_sigma[k] += std::abs(c.hover_endurance_s - flown_s) <= c.hover_endurance_std_s;
        within_2sigma[k] += std::abs(c.hover_endurance_s - flown_s) <= 2.0 * c.hover_endurance_std_s;
        errors[k].push_back(std::abs(error));
      }
    }
  }
  std::printf("within 15 %% after 20 s: %d of %d; within 10 %% after 60 s: %d of %d\n", within_bar[0], cases[0],
              within_bar[1], cases[1]);
  std::printf("the truth within the stated 1 / 2 standard deviations: after 20 s %d / %d, after 60 s %d / %d of %d\n",
              within_sigma[0], within_2sigma[0], within_sigma[1], within_2sigma[1], cases[1]);
  // Issue 19's bar (within 15 % after 20 s and 10 % after 60 s, every case) does NOT hold on this
  // family (docs/capability.md: the knee of a pack's curve that is not ours, its slow polarisation
  // and a cold pack's lost capacity). What is asserted is a regression guard on the median error
  // after 60 s, the measured figures printed above.
  std::nth_element(errors[1].begin(), errors[1].begin() + errors[1].size() / 2, errors[1].end());
  EXPECT_LT(errors[1][errors[1].size() / 2], median_bound);
}

// Why issue 19's bar (every case within 10 % after 60 s) cannot be met from cells, capacity and the
// cut-off alone. Two packs: one of the family (seed 19: two plateaus, 14 C, 40 mOhm in all, which
// sags it to the cut-off where its curve still bends; picked among 13 drawn packs as one where the
// knee decides, as a counter-example needs only one: seed 8's ratio is about 1.23) and the same
// pack with its curve lowered below 22 % charge, to 5 mV above the family's lowest resting voltage
// at 10 % (the spread of published LiPo charts), a quadratic dip that keeps the curve rising.
// Hovering from 30 %, the first minute never goes below 22 %: every message the node gets is the same, so is any
// estimator's prediction, but the packs reach the loaded cut-off at different times. When the
// longer is more than 1.1 / 0.9 of the shorter, no prediction lies within 10 % of both.
TEST(CapabilityFlight, TwoPacksAlikeAboveTheirKneeGetOnePredictionButNotOneHoverTime) {
  const pe::sim::BatteryFamily family;
  pe::sim::SimParams alike = thesisParams();
  alike.battery = pe::sim::drawBattery(family, 19).params;
  pe::sim::SimParams lower_knee = alike;
  pe::sim::LipoBatteryParams& lowered = lower_knee.battery;
  constexpr double kAboveSoc = 0.22;
  const auto dip = [](double soc) { return std::pow(std::max(0.0, kAboveSoc - soc) / kAboveSoc, 2); };
  const double depth_v =
      (alike.battery.openCircuitVoltage(0.1) / family.cells - (family.cell_v_at[0].lo + 0.005)) / dip(0.1);
  ASSERT_GT(depth_v, 0.0);
  for (std::size_t k = 0; k < lowered.ocv_soc.size(); ++k) lowered.ocv_cell_v[k] -= depth_v * dip(lowered.ocv_soc[k]);
  lowered.validate();
  // Still a pack of the family's spread at empty and at 10 %.
  EXPECT_GE(lowered.ocv_cell_v.front(), family.cell_empty_v.lo);
  EXPECT_GE(lowered.openCircuitVoltage(0.1) / family.cells, family.cell_v_at[0].lo);

  std::array<double, 2> predicted_s{}, flown_s{};
  for (std::size_t k = 0; k < 2; ++k) {
    CapabilitySink sink(f450(), userPack(), thesisModel(), {60.0});
    fly(profile(0.0, 3000.0, 0.3), &sink, {}, k == 0 ? alike : lower_knee);
    ASSERT_TRUE(sink.cutoff_s.has_value());
    ASSERT_TRUE(sink.predictions[0].has_value());
    predicted_s[k] = sink.predictions[0]->report.hover_endurance_s;
    flown_s[k] = *sink.cutoff_s - sink.predictions[0]->made_s;
  }
  std::printf("the curve lowered below %.0f %% by up to %.3f V a cell: predicted %.1f and %.1f s after 60 s, flew %.0f and "
              "%.0f s (ratio %.2f; within 10 %% of both needs at most %.2f)\n",
              100.0 * kAboveSoc, depth_v, predicted_s[0], predicted_s[1], flown_s[0], flown_s[1],
              flown_s[0] / flown_s[1], 1.1 / 0.9);
  EXPECT_EQ(predicted_s[0], predicted_s[1]);
  EXPECT_GT(flown_s[0], 1.1 / 0.9 * flown_s[1]);
}

// The payload limit predicted at the first hover against the simulated vehicle's at full throttle:
// the simulated propulsion at the model's top PWM fed by the pack as it is then (its EMF, the
// terminal voltage plus its series resistance times the current), sagging through its series and
// the supply resistance at the full-throttle current, the airframe's thrust loss applied; with
// and without effects in the simulator and the model's effects: section. `model` gives the model
// with an effects: section (YAML) appended; the figures are within `bar` of the payload limit, or
// of the all-up mass at the limit when `of_all_up_mass`.
void expectPayloadLimitAgainstFullThrottleWithSag(const std::function<pe::PropulsionModel(const std::string&)>& model,
                                                  double bar, bool of_all_up_mass) {
  const std::string effects_yaml = "effects:\n  supply_resistance: {resistance_ohm: 0.05}\n  thrust_loss: {fraction: 0.06}\n";
  pe::sim::SimEffects injected;
  injected.supply_resistance_ohm = 0.05;
  injected.thrust_loss_fraction = 0.06;
  for (const bool with_effects : {false, true}) {
    for (std::uint32_t seed : {7u, 8u}) {
      const double payload_kg = seed == 7 ? 0.0 : 0.2;
      pe::sim::SimParams params = thesisParams();
      params.battery = pe::sim::drawBattery(pe::sim::BatteryFamily{}, seed).params;
      CapabilitySink sink(f450(), userPack(), model(with_effects ? effects_yaml : ""));
      fly(profile(payload_kg, 20.0, 0.9), &sink, with_effects ? injected : pe::sim::SimEffects{}, params);
      ASSERT_TRUE(sink.prediction.has_value());
      const pe::sim::TruthSample& truth = sink.prediction_truth;
      const pe::sim::PropulsionChain chain(params.chain);
      const double source_v = truth.battery_voltage_v + params.battery.series_resistance_ohm * truth.battery_current_a;
      const double path_ohm = params.battery.series_resistance_ohm + (with_effects ? 0.05 : 0.0);
      const pe::sim::ChainInput input{params.chain.esc.duty(sink.prediction->pwm_max_us), 0.0, truth.air_density_kg_m3,
                                      params.chain.motor.reference_temperature_c};
      double esc_v = 0.0;
      const pe::sim::ChainState top = chain.steadyFromSource(input, source_v, path_ohm, 4, &esc_v);
      const double thrust_n = top.thrust_n * 4 * (with_effects ? 0.94 : 1.0);
      const double limit_kg = thrust_n / (pe::kStandardGravity * 1.6) - (truth.total_mass_kg - payload_kg);
      const double predicted_kg = payload_kg + sink.prediction->max_additional_payload_kg;
      // The sag at full throttle as the simulated pack gives it (terminal voltage and current)...
      const double terminal_v = source_v - params.battery.series_resistance_ohm * 4 * top.input_current_a;
      EXPECT_NEAR(sink.prediction->full_throttle_voltage_v, terminal_v, 0.1) << "effects " << with_effects;
      EXPECT_NEAR(sink.prediction->full_throttle_current_a, 4 * top.input_current_a, 0.05 * 4 * top.input_current_a);
      // ... and the limit.
      const double all_up_kg = thrust_n / (pe::kStandardGravity * 1.6);
      EXPECT_NEAR(predicted_kg, limit_kg, bar * (of_all_up_mass ? all_up_kg : std::abs(limit_kg)))
          << "payload " << payload_kg << ", effects " << with_effects << ": " << sink.prediction->payload_note;
      EXPECT_LT(sink.prediction->max_additional_payload_at_cutoff_kg, sink.prediction->max_additional_payload_kg);
      std::printf("effects %s, carrying %.3f kg: payload limit %.3f kg predicted (full throttle %.2f V, %.1f A), "
                  "%.3f kg simulated (%.2f V at the ESCs, %.1f A): %+.1f %% of the limit, %+.1f %% of the all-up mass\n",
                  with_effects ? "on" : "off", payload_kg, predicted_kg, sink.prediction->full_throttle_voltage_v,
                  sink.prediction->full_throttle_current_a, limit_kg, esc_v, 4 * top.input_current_a,
                  100.0 * (predicted_kg - limit_kg) / std::abs(limit_kg), 100.0 * (predicted_kg - limit_kg) / all_up_kg);
    }
  }
}

// A model fitted, as a user would, on the simulated thrust stand of the vehicle's own propulsion
// (PWM sweeps at 10.5-12.6 V with the stand's sensor noise, seed 3; fit_surfaces' choice of surface).
pe::PropulsionModel benchFittedModel(const std::string& effects) {
  static const std::string fitted = [] {
    const pe::sim::SimParams params = thesisParams();
    const pe::sim::BenchExperiment sweep =
        pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
    pe::fitting::FitOptions options;
    options.air_temperature_c = 20.0;
    options.air_pressure_pa = 101325.0;
    const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel({pe::sim::simulateBench(params, {}, sweep, 3)}, options);
    EXPECT_TRUE(fit.validation_error.empty()) << fit.validation_error;
    return pe::modelToYaml(fit.model);
  }();
  return pe::parseModelYaml(fitted + effects, "bench-fitted model");
}

}  // namespace

// Development seeds chose the estimator's settings; held-out seeds were first run after them; fresh
// seeds were drawn on 2026-11-25 after the settings were fixed and first run then.
const std::vector<std::uint32_t> kDevelopmentSeeds = {1, 2, 3, 4, 5, 6};
const std::vector<std::uint32_t> kHeldOutSeeds = {101, 102, 103, 104, 105, 106};
const std::vector<std::uint32_t> kFreshSeeds = {1551, 2927, 4567, 5106, 6016, 9449};

std::vector<std::uint32_t> allEnduranceSeeds() {
  std::vector<std::uint32_t> seeds = kDevelopmentSeeds;
  seeds.insert(seeds.end(), kHeldOutSeeds.begin(), kHeldOutSeeds.end());
  seeds.insert(seeds.end(), kFreshSeeds.begin(), kFreshSeeds.end());
  return seeds;
}

TEST(CapabilityFlight, HoverEnduranceOnFamilyPacksDevelopmentSeeds) { expectEnduranceOnFamilyPacks(kDevelopmentSeeds); }

TEST(CapabilityFlight, HoverEnduranceOnFamilyPacksHeldOutSeeds) { expectEnduranceOnFamilyPacks(kHeldOutSeeds); }

TEST(CapabilityFlight, HoverEnduranceOnFamilyPacksFreshSeeds) { expectEnduranceOnFamilyPacks(kFreshSeeds); }

// The same packs, the user also giving the pack's own open-circuit curve (capability/battery/
// ocv_table; here the simulator's own table, an ideal measurement): what is left is the
// polarisation a minute shows only in part and a cold or aged pack's lost capacity.
TEST(CapabilityFlight, HoverEnduranceWithThePacksOwnCurve) { expectEnduranceOnFamilyPacks(allEnduranceSeeds(), 0.15, true); }

// Packs of the family at 25 C, new (no fade, no resistance growth), with the fast RC pair only,
// given their own curve: what is left is the polarisation the least squares sees within its memory.
TEST(CapabilityFlight, HoverEnduranceWithTheOwnCurveOfWarmNewPacks) {
  pe::sim::BatteryFamily warm_new;
  warm_new.temperature_c = {25.0, 25.0};
  warm_new.capacity_fade = {0.0, 0.0};
  warm_new.resistance_growth = {0.0, 0.0};
  warm_new.second_rc_probability = 0.0;
  expectEnduranceOnFamilyPacks(allEnduranceSeeds(), 0.06, true, warm_new);
}

// With the thesis surfaces, whose thrust at full throttle is 1.8-3.6 % above the simulator's
// physics: the limit within 5 % of the all-up mass at the limit, not within 10 % of the limit
// itself (a difference of two masses, so the surfaces' excess is multiplied; docs/capability.md).
TEST(CapabilityFlight, PayloadLimitAgainstTheSimulatedFullThrottleWithSag) {
  expectPayloadLimitAgainstFullThrottleWithSag([](const std::string& effects) { return thesisModel(effects); }, 0.05, true);
}

// With surfaces measured on the vehicle's own propulsion (here its simulated bench): issue 19's
// bar, within 10 % of the limit, with and without effects.
TEST(CapabilityFlight, PayloadLimitWithSurfacesFittedOnTheVehiclesOwnBench) {
  expectPayloadLimitAgainstFullThrottleWithSag(benchFittedModel, 0.10, false);
}

// The F450's healthy fingerprint from three healthy flights of its own (seeds 21-23, the centre of
// gravity 9 mm off), learned as diagnose_gap --reference learns it: each motor's mean model thrust
// over the hover.
pe::MotorReference f450Reference() {
  std::vector<pe::HoverThrusts> healthy;
  for (unsigned seed : {21u, 22u, 23u}) {
    CapabilitySink sink(f450(), userPack());
    fly(profile(0.0, 40.0, 0.9, "[0.008, -0.005, 0.0]"), &sink, {}, thesisParams(), seed);
    for (double& thrust : sink.hover_thrust_n) thrust /= sink.hover_samples;
    healthy.push_back(sink.hover_thrust_n);
  }
  return pe::learnMotorReference(f450(), healthy);
}

std::string weakPropeller(int motor, double factor) {
  return "faults: {weak_propeller: {motor: " + std::to_string(motor) + ", thrust_factor: " + std::to_string(factor) +
         ", damage: chipped}}\n";
}

TEST(CapabilityFlight, AWeakPropellerIsFlaggedWithin20sOfSteadyHoverAgainstTheVehiclesReference) {
  const pe::MotorReference reference = f450Reference();
  for (const auto& [motor, factor] : {std::pair<int, double>{3, 0.85}, {1, 0.9}, {4, 0.8}}) {
    CapabilitySink sink(f450(), userPack(), thesisModel(), {}, reference);
    fly(profile(0.0, 40.0, 0.9, "[0.008, -0.005, 0.0]", weakPropeller(motor, factor)), &sink);
    ASSERT_TRUE(sink.hover_start_s.has_value());
    ASSERT_TRUE(sink.first_flag_s.has_value()) << "motor " << motor;
    EXPECT_EQ(sink.flagged_channels, 1u << motor) << "motor " << motor;
    EXPECT_LE(*sink.first_flag_s - *sink.hover_start_s, 20.0) << "motor " << motor;
    // A chipped propeller loses torque too, so its rotor spins up: the thrust it lacks at its PWM
    // is less than its thrust coefficient's loss.
    EXPECT_NEAR(sink.last_health->motors[motor - 1].thrust_gap, 1.0 - factor, 0.05) << "motor " << motor;
  }
}

// Without a reference a motor is flagged only beyond the spread healthy vehicles show against the
// ideal balance (three times 6.7 %): a propeller at 70 % is, one at 85 % is not.
TEST(CapabilityFlight, WithoutAReferenceOnlyAGrossFaultIsFlagged) {
  for (const auto& [factor, flagged] : {std::pair<double, unsigned>{0.85, 0u}, {0.7, 1u << 3}}) {
    CapabilitySink sink(f450(), userPack());
    fly(profile(0.0, 40.0, 0.9, "[0.008, -0.005, 0.0]", weakPropeller(3, factor)), &sink);
    EXPECT_EQ(sink.flagged_channels, flagged) << factor;
  }
}

TEST(CapabilityFlight, ACentreOfGravityOffsetIsToldApartFromAMotorFault) {
  for (const std::string offset : {"[0.01, 0.0, 0.0]", "[-0.00707, 0.00707, 0.0]"}) {
    CapabilitySink sink(f450(), userPack());
    fly(profile(0.3, 40.0, 0.9, offset), &sink);
    ASSERT_TRUE(sink.last_health.has_value());
    EXPECT_EQ(sink.flagged_channels, 0u) << offset;
    EXPECT_NEAR(std::hypot(sink.last_health->cg_offset_x_m, sink.last_health->cg_offset_y_m), 0.01 * 1.315 / 1.615,
                0.004)
        << offset;
  }
}

// The capability answers on simulated flights, the core estimator fed as the node feeds it: the
// payload limit against the simulated propulsion's thrust at the top PWM with the pack sagging; a
// weak propeller flagged, a centre-of-gravity offset not. The hover endurance is in
// test_hover_endurance_flight.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "capability_flight.h"
#include "propulsion_estimator/fitting/surface_fit.h"
#include "propulsion_estimator/sim/physics/battery_family.h"
#include "propulsion_estimator/sim/stand/bench_simulator.h"

using namespace capability_flight;

namespace {
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

// The capability answers on simulated flights, the core estimator fed as the node feeds it: the
// hover endurance predicted at the first hover against the time the simulated vehicle, hovering
// on, takes to reach the cut-off voltage; the payload limit against the simulated propulsion's
// thrust at the top PWM; a weak propeller flagged, a centre-of-gravity offset not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "propulsion_estimator/common/simulation_error.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/onboard/capability.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/propulsion_chain.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

constexpr double kCellCutoffV = 3.5;

pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

// The share of the simulated pack's capacity drawn when its terminal voltage reaches the cut-off
// under a steady `current_a`: where its open-circuit voltage less the current through its series
// and polarisation resistances is the cut-off. What its owner reads off the pack's discharge chart
// at the hover's C-rate for usable_fraction.
double usableFraction(const pe::sim::LipoBatteryParams& battery, double current_a) {
  const double cell_v =
      kCellCutoffV + current_a * (battery.series_resistance_ohm + battery.rc_resistance_ohm) / battery.cells;
  for (std::size_t k = 1; k < battery.ocv_soc.size(); ++k) {
    if (battery.ocv_cell_v[k] < cell_v) continue;
    const double share = (cell_v - battery.ocv_cell_v[k - 1]) / (battery.ocv_cell_v[k] - battery.ocv_cell_v[k - 1]);
    return 1.0 - (battery.ocv_soc[k - 1] + share * (battery.ocv_soc[k] - battery.ocv_soc[k - 1]));
  }
  return 0.0;
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
// health after each accepted RCOut, and evaluates the capability once a second.
class CapabilitySink : public pe::sim::FlightSink {
 public:
  CapabilitySink(const pe::Vehicle& vehicle, const pe::CapabilityConfig& config)
      : model_(pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"))),
        estimator_(model_, vehicle, {}),
        health_(vehicle, {1, 2, 3, 4}, config.motor_health),
        capability_(estimator_.model(), 4, config),
        cutoff_v_(*config.cells * config.cell_cutoff_v) {}

  void rcOut(const pe::sim::RcOutSample& s) override {
    if (estimator_.addMotorOutputs(s.time_s, s.time_s, s.channels.data(), s.channels.size()) != pe::Rejection::kNone) {
      return;
    }
    const pe::EstimatorOutput& out = estimator_.output();
    health_.add(out);
    if (out.hover.hovering && !hover_start_s) hover_start_s = s.time_s;
    if (s.time_s < next_evaluation_s_) return;
    next_evaluation_s_ = s.time_s + 1.0;
    const pe::MotorHealthVerdict verdict = health_.verdict();
    if (verdict.judged) last_health = verdict;
    if (verdict.flagged_channel != 0) {
      if (!first_flag_s) first_flag_s = s.time_s;
      flagged_channels |= 1u << verdict.flagged_channel;
    }
    // The first hover's prediction: once the payload estimate averages a whole window.
    if (!prediction && out.payload.state == pe::PayloadState::kHovering && out.payload.window_s >= 9.5) {
      prediction = capability_.evaluate(out, battery_);
      prediction_s = s.time_s;
      prediction_voltage_v = truth_voltage_v_;
      prediction_density = truth_density_;
      prediction_mass_kg = truth_mass_kg_;
    }
  }
  void battery(const pe::sim::BatterySample& s) override {
    estimator_.addBattery(s.time_s, s.voltage_v);
    battery_ = pe::BatteryReport{s.percentage, pe::kNaN, s.current_a};
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
  void truth(const pe::sim::TruthSample& s) override {
    truth_voltage_v_ = s.battery_voltage_v;
    truth_density_ = s.air_density_kg_m3;
    truth_mass_kg_ = s.total_mass_kg;
    if (prediction && !cutoff_s && s.battery_voltage_v < cutoff_v_) cutoff_s = s.time_s;
  }

  std::optional<double> hover_start_s, first_flag_s, cutoff_s;
  unsigned flagged_channels = 0;
  std::optional<pe::MotorHealthVerdict> last_health;
  std::optional<pe::CapabilityReport> prediction;
  double prediction_s = 0.0, prediction_voltage_v = 0.0, prediction_density = 0.0, prediction_mass_kg = 0.0;

 private:
  pe::PropulsionModel model_;
  pe::Estimator estimator_;
  pe::MotorHealth health_;
  pe::CapabilityEstimator capability_;
  double cutoff_v_;
  double next_evaluation_s_ = 0.0;
  pe::BatteryReport battery_;
  double truth_voltage_v_ = 0.0, truth_density_ = 0.0, truth_mass_kg_ = 0.0;
};

pe::CapabilityConfig simulatedPack() {
  const pe::sim::SimParams params = thesisParams();
  pe::CapabilityConfig config;
  config.capacity_ah = params.battery.capacity_ah;
  config.cells = params.battery.cells;
  config.cell_cutoff_v = kCellCutoffV;
  // 4C, 16 A: the thesis quad hovers on 13-15 A empty and 18-19 A with 0.3 kg.
  config.usable_fraction = usableFraction(params.battery, 4.0 * params.battery.capacity_ah);
  return config;
}

// Flies `text`; a flight that outlasts its battery ends there (the endurance flights hover on
// until it is empty).
void fly(const std::string& text, CapabilitySink* sink, pe::sim::SimEffects effects = {}) {
  const pe::sim::FlightProfile flight = pe::sim::parseFlightProfileYaml(text, "capability_flight.yaml");
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(flight.vehicle.urdf_path);
  try {
    pe::sim::simulateFlight(thesisParams(), effects, flight, vehicle, 11, sink);
  } catch (const pe::SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("the battery is empty"), std::string::npos) << e.what();
  }
}

pe::Vehicle f450() { return pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf")); }

void expectEnduranceWithinTenPercent(double payload_kg) {
  CapabilitySink sink(f450(), simulatedPack());
  fly(profile(payload_kg, 3000.0, 0.5), &sink);
  ASSERT_TRUE(sink.prediction.has_value());
  ASSERT_TRUE(sink.cutoff_s.has_value());
  const double flown_s = *sink.cutoff_s - sink.prediction_s;
  EXPECT_EQ(sink.prediction->charge_basis, "percentage");
  EXPECT_NEAR(sink.prediction->hover_endurance_s, flown_s, 0.1 * flown_s)
      << "payload " << payload_kg << " kg, " << sink.prediction->endurance_basis;
  std::printf("payload %.3f kg: predicted %.0f s at t = %.0f s, the simulated vehicle reached %.2f V after %.0f s\n",
              payload_kg, sink.prediction->hover_endurance_s, sink.prediction_s, 3 * kCellCutoffV, flown_s);
}

}  // namespace

TEST(CapabilityFlight, HoverEnduranceOfTheEmptyVehicleWithinTenPercent) { expectEnduranceWithinTenPercent(0.0); }

TEST(CapabilityFlight, HoverEnduranceWithAPayloadWithinTenPercent) { expectEnduranceWithinTenPercent(0.3); }

TEST(CapabilityFlight, PayloadLimitWithinTenPercentOfTheSimulatedThrustToWeightLimit) {
  for (double payload_kg : {0.0, 0.2}) {
    CapabilitySink sink(f450(), simulatedPack());
    fly(profile(payload_kg, 20.0, 0.9), &sink);
    ASSERT_TRUE(sink.prediction.has_value());
    // The simulated propulsion at the model's top PWM at the battery voltage of the moment: the
    // payload at which the simulated vehicle's thrust-to-weight reaches the limit.
    const pe::sim::SimParams params = thesisParams();
    const pe::sim::PropulsionChain chain(params.chain);
    const double thrust_n =
        4 * chain
                .steady({params.chain.esc.duty(sink.prediction->pwm_max_us), sink.prediction_voltage_v,
                         sink.prediction_density, params.chain.motor.reference_temperature_c})
                .thrust_n;
    const double limit_kg = thrust_n / (pe::kStandardGravity * 1.6) - (sink.prediction_mass_kg - payload_kg);
    const double predicted_kg = payload_kg + sink.prediction->max_additional_payload_kg;
    EXPECT_NEAR(predicted_kg, limit_kg, 0.1 * limit_kg) << "payload " << payload_kg;
    EXPECT_LT(sink.prediction->max_additional_payload_at_cutoff_kg, sink.prediction->max_additional_payload_kg);
    std::printf("carrying %.3f kg: payload limit %.3f kg predicted (%.3f kg more), %.3f kg simulated\n", payload_kg,
                predicted_kg, sink.prediction->max_additional_payload_kg, limit_kg);
  }
}

TEST(CapabilityFlight, AWeakPropellerIsFlaggedWithin20sOfSteadyHover) {
  for (const auto& [motor, factor] : {std::pair<int, double>{3, 0.85}, {1, 0.9}, {4, 0.8}}) {
    CapabilitySink sink(f450(), simulatedPack());
    fly(profile(0.0, 40.0, 0.9, "[0.008, -0.005, 0.0]",
                "faults: {weak_propeller: {motor: " + std::to_string(motor) + ", thrust_factor: " +
                    std::to_string(factor) + "}}\n"),
        &sink);
    ASSERT_TRUE(sink.hover_start_s.has_value());
    ASSERT_TRUE(sink.first_flag_s.has_value()) << "motor " << motor;
    EXPECT_EQ(sink.flagged_channels, 1u << motor) << "motor " << motor;
    EXPECT_LE(*sink.first_flag_s - *sink.hover_start_s, 20.0) << "motor " << motor;
    EXPECT_NEAR(sink.last_health->motors[motor - 1].thrust_gap, 1.0 - factor, 0.05) << "motor " << motor;
  }
}

TEST(CapabilityFlight, ACentreOfGravityOffsetIsToldApartFromAMotorFault) {
  for (const std::string offset : {"[0.01, 0.0, 0.0]", "[-0.00707, 0.00707, 0.0]"}) {
    CapabilitySink sink(f450(), simulatedPack());
    fly(profile(0.3, 40.0, 0.9, offset), &sink);
    ASSERT_TRUE(sink.last_health.has_value());
    EXPECT_EQ(sink.flagged_channels, 0u) << offset;
    EXPECT_NEAR(std::hypot(sink.last_health->cg_offset_x_m, sink.last_health->cg_offset_y_m), 0.01 * 1.315 / 1.615,
                0.004)
        << offset;
  }
}

// The capability tests' simulated flights: the thesis quad's model and simulated propulsion, a
// take-off and hover profile, and a sink that feeds the core estimator, the motor health and the
// capability as the node does, keeping the predictions and when the simulated pack reached its cut-off.
#pragma once

#include <gtest/gtest.h>


#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "propulsion_estimator/common/simulation_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/onboard/capability.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/estimation/motor_change.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/battery_family.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace capability_flight {

inline constexpr double kCellCutoffV = 3.5;

// The thesis quad's model; `effects` an effects: section for it (YAML), or none.
inline pe::PropulsionModel thesisModel(const std::string& effects = "") {
  return pe::parseModelYaml(pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml")) + effects, "thesis model");
}

inline pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

// Take-off to 2 m and a hover of `hover_s` with `payload_kg` on a 0.3 m cable, from
// `initial_soc`, the centre of gravity `cg_offset` off the URDF's; `faults` a profile section;
// `rest_after_s` on the ground after landing; `avionics_current_a` drawn from the battery beside the
// ESCs (flight controller, companion computer, radios).
inline std::string profile(double payload_kg, double hover_s, double initial_soc, const std::string& cg_offset = "[0.0, 0.0, 0.0]",
                    const std::string& faults = "", double rest_after_s = 2.0, double avionics_current_a = 0.0) {
  std::string text = "autopilot: {flavour: px4, pwm_min_us: 1100, pwm_max_us: 1950, disarmed_pwm_us: 900, "
                     "rc_out_rate_hz: 50}\n"
                     "vehicle: {urdf: " +
                     repoPath("config/f450_quad.urdf") + ", centre_of_mass_offset_m: " + cg_offset +
                     ", landing_gear: {height_m: 0.12, half_width_m: 0.12}, drag_area_m2: 0.04, "
                     "battery_initial_soc: " +
                     std::to_string(initial_soc) + ", avionics_current_a: " + std::to_string(avionics_current_a) +
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
          "  - {type: wait, duration_s: " +
          std::to_string(rest_after_s) + "}\n";
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
                                  truth_.battery_current_a, lowest_true_soc};
    }
  }
  /// `previous` with the flight learned (the pack file's next record), once it has finished.
  pe::PackRecord learnPack(const pe::PackRecord& previous) { return capability_.learnPack(previous); }
  bool packFlightFinished() const { return capability_.packFlightFinished(); }

  void battery(const pe::sim::BatterySample& s) override {
    estimator_.addBattery(s.time_s, s.voltage_v);
    estimator_.addBatteryCurrent(s.time_s, s.current_a);
    // The simulated percentage is the true state of charge: the default mode (ignore) never reads it.
    if (std::isnan(lowest_true_soc) || s.percentage < lowest_true_soc) lowest_true_soc = s.percentage;
    const double modelled_a = estimator_.output().totals.current_a;
    capability_.addBattery(s.time_s, s.voltage_v, pe::BatteryReport{s.percentage, s.current_a, pack_temperature_c},
                           modelled_a);
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
    if (takeoff_s && s.time_s > *takeoff_s + 5.0 && !cutoff_s && filtered_v_ < cutoff_v_) {
      cutoff_s = s.time_s;
      cutoff_true_soc = lowest_true_soc;
    }
  }

  /// deg C the battery messages report for the pack (BatteryState.temperature); NaN: none.
  double pack_temperature_c = pe::kNaN;
  /// The simulated pack's lowest state of charge in the flight, as its BatteryState.percentage
  /// reports it (the simulator's truth rounded to 1 %): where a counter-example may change the
  /// pack's curve unseen.
  double lowest_true_soc = pe::kNaN;
  /// lowest_true_soc when the cut-off was reached (NaN before): where the pack's usable charge ends.
  double cutoff_true_soc = pe::kNaN;
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
    double lowest_true_soc;  ///< the simulated pack's lowest state of charge until then
  };
  std::vector<std::optional<Prediction>> predictions;
};

// What the user of the thesis quad's pack gives: cells, rated capacity, the cut-off.
inline pe::CapabilityConfig userPack(int cells = 3, double capacity_ah = 4.0) {
  pe::CapabilityConfig config;
  config.capacity_ah = capacity_ah;
  config.cells = cells;
  config.cell_cutoff_v = kCellCutoffV;
  return config;
}

// Flies `text`; a flight that outlasts its battery ends there (the endurance flights hover on
// until it is empty).
inline void fly(const std::string& text, CapabilitySink* sink, pe::sim::SimEffects effects = {},
         const pe::sim::SimParams& params = thesisParams(), unsigned seed = 11) {
  const pe::sim::FlightProfile flight = pe::sim::parseFlightProfileYaml(text, "capability_flight.yaml");
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(flight.vehicle.urdf_path);
  try {
    pe::sim::simulateFlight(params, effects, flight, vehicle, seed, sink);
  } catch (const pe::SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("the battery is empty"), std::string::npos) << e.what();
  }
}

inline pe::Vehicle f450() { return pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf")); }

// A of avionics beside the ESCs on the flights of pack `seed`: 0.3-1.5 A, a value of its own per
// pack (a flight controller and radios to a companion computer and a camera), never zero.
inline double avionicsA(std::uint32_t seed) { return 0.3 + 1.2 * ((seed * 2654435761u) % 1000u) / 1000.0; }

// The long tests fly their packs on every core (each pack on its own objects), their lines
// printed in the order of the seeds once every pack has flown.
inline const int kCores = static_cast<int>(std::thread::hardware_concurrency());

// printf's text appended to `log`.
inline void appendf(std::string* log, const char* format, ...) __attribute__((format(printf, 2, 3)));
inline void appendf(std::string* log, const char* format, ...) {
  char line[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof line, format, args);
  va_end(args);
  *log += line;
}

// Lowers `battery`'s curve below `above_soc` (a table point there, or none below it changes the
// curve above) by a quadratic dip that keeps it rising: as deep as keeps it 5 mV above the
// family's lowest resting voltage at 10 % (the spread of published LiPo charts) and no lower than
// the family's lowest at empty. Returns the depth in V a cell; at or below 0 (the pack already at
// the charts' lowest at 10 %, or above_soc not above 10 %) nothing is lowered.
inline double lowerCurveBelow(pe::sim::LipoBatteryParams* battery, double above_soc, const pe::sim::BatteryFamily& family) {
  const auto dip = [above_soc](double soc) { return std::pow(std::max(0.0, above_soc - soc) / above_soc, 2); };
  if (!(above_soc > 0.1)) return 0.0;
  const double depth_v =
      std::min((battery->openCircuitVoltage(0.1) / battery->cells - (family.cell_v_at[0].lo + 0.005)) / dip(0.1),
               battery->ocv_cell_v.front() - family.cell_empty_v.lo);
  if (!(depth_v > 0.0)) return depth_v;
  for (std::size_t k = 0; k < battery->ocv_soc.size(); ++k) battery->ocv_cell_v[k] -= depth_v * dip(battery->ocv_soc[k]);
  battery->validate();
  return depth_v;
}

}  // namespace capability_flight

#pragma once

// A short simulated flight for the flight-log readers' round trips: take off to 1 m, hover 8 s,
// land, rc/out at 25 Hz, every message to two sinks (a recorder and a log writer).
#include <string>

#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "recording_flight_sink.h"
#include "test_paths.h"

// Both sinks get every message.
struct TeeFlightSink : propulsion_estimator::sim::FlightSink {
  using Sink = propulsion_estimator::sim::FlightSink;
  TeeFlightSink(Sink* a, Sink* b) : a_(a), b_(b) {}
  void rcOut(const propulsion_estimator::sim::RcOutSample& s) override { a_->rcOut(s), b_->rcOut(s); }
  void battery(const propulsion_estimator::sim::BatterySample& s) override { a_->battery(s), b_->battery(s); }
  void imu(const propulsion_estimator::sim::ImuSample& s) override { a_->imu(s), b_->imu(s); }
  void pose(const propulsion_estimator::sim::PoseSample& s) override { a_->pose(s), b_->pose(s); }
  void velocity(const propulsion_estimator::sim::VelocitySample& s) override { a_->velocity(s), b_->velocity(s); }
  void staticPressure(const propulsion_estimator::sim::ScalarSample& s) override {
    a_->staticPressure(s), b_->staticPressure(s);
  }
  void airTemperature(const propulsion_estimator::sim::ScalarSample& s) override {
    a_->airTemperature(s), b_->airTemperature(s);
  }
  void rangefinder(const propulsion_estimator::sim::RangeSample& s) override { a_->rangefinder(s), b_->rangefinder(s); }
  void motorTemperature(const propulsion_estimator::sim::ScalarSample& s) override {
    a_->motorTemperature(s), b_->motorTemperature(s);
  }
  void truth(const propulsion_estimator::sim::TruthSample& s) override { a_->truth(s), b_->truth(s); }
  Sink* a_;
  Sink* b_;
};

// Flies the short flight into `recorded` and `log`.
inline void simulateShortFlight(RecordingFlightSink* recorded, propulsion_estimator::sim::FlightSink* log) {
  namespace pe = propulsion_estimator;
  const std::string profile_text =
      "autopilot: {flavour: px4, pwm_min_us: 1100, pwm_max_us: 1950, disarmed_pwm_us: 900, rc_out_rate_hz: 25}\n"
      "vehicle:\n  urdf: " +
      repoPath("config/f450_quad.urdf") +
      "\n  centre_of_mass_offset_m: [0, 0, 0]\n  landing_gear: {height_m: 0.12, half_width_m: 0.12}\n"
      "  drag_area_m2: 0.04\n  battery_initial_soc: 0.9\n"
      "payload_cable: {length_m: 1.0, attach_point_m: [0, 0, -0.04], stiffness_n_per_m: 1000, damping_n_s_per_m: 10}\n"
      "manifest: {settle_s: 3}\n"
      "segments:\n  - {type: wait, duration_s: 1}\n  - {type: takeoff, height_m: 1.0, rate_m_s: 1.0}\n"
      "  - {type: hover, duration_s: 8}\n  - {type: land, rate_m_s: 1.0}\n";
  const pe::sim::FlightProfile profile = pe::sim::parseFlightProfileYaml(profile_text, "profile.yaml");
  TeeFlightSink tee(recorded, log);
  pe::sim::simulateFlight(pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")), {}, profile,
                          pe::loadVehicleUrdf(profile.vehicle.urdf_path), 1, &tee);
}

#pragma once

// A short simulated flight for the flight-log readers' round trips: take off to 1 m, hover 8 s,
// land, rc/out at 25 Hz, every message to two sinks (a recorder and a log writer).
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "propulsion_estimator/logs/flight_streams.h"
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
  void escTelemetry(const propulsion_estimator::sim::EscTelemetrySample& s) override {
    a_->escTelemetry(s), b_->escTelemetry(s);
  }
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

// The streams a log reader read back against what the simulator emitted: every signal's count, and
// values within the log's precision (floats); `pwm_tolerance_us` > 0 for outputs logged normalised.
inline void expectRoundTrip(const propulsion_estimator::FlightStreams& read, const RecordingFlightSink& sim,
                            double pwm_tolerance_us) {
  namespace pe = propulsion_estimator;
  ASSERT_EQ(read.rc_out.size(), sim.rc_out.size());
  for (std::size_t i = 0; i < sim.rc_out.size(); i += 7) {
    EXPECT_NEAR(read.rc_out[i].time_s, sim.rc_out[i].time_s, 1e-6);
    for (int k = 0; k < 4; ++k) {
      // Stopped motors (below the range, logged NaN when normalised) read as 0 us, not driven.
      const double sent = sim.rc_out[i].channels[k];
      const double pwm = pwm_tolerance_us > 0 && sent < 1100.0 ? 0.0 : sent;
      EXPECT_NEAR(read.rc_out[i].pwm_us[k], pwm, pwm_tolerance_us + 1e-3) << i;
    }
  }
  ASSERT_EQ(read.battery.size(), sim.batteries.size());
  EXPECT_NEAR(read.battery.back().voltage_v, sim.batteries.back().voltage_v, 1e-5);
  EXPECT_NEAR(read.battery.back().current_a, sim.batteries.back().current_a, 1e-5);
  ASSERT_EQ(read.imu.size(), sim.imus.size());
  for (std::size_t i = 0; i < sim.imus.size(); i += 13) {
    EXPECT_LT(read.imu[i].orientation.angularDistance(sim.imus[i].orientation), 1e-6) << i;
    EXPECT_LT((read.imu[i].specific_force_m_s2 - sim.imus[i].linear_acceleration_m_s2).norm(), 1e-5) << i;
  }
  ASSERT_EQ(read.altitude_m.size(), sim.velocities.size());
  EXPECT_NEAR(read.altitude_m[200].value, sim.poses[200].position_m.z(), 1e-6);
  EXPECT_NEAR(read.vertical_speed_m_s[200].value, sim.velocities[200].linear_m_s.z(), 1e-6);
  ASSERT_EQ(read.input(pe::input::Scalar::kStaticPressure).size(), sim.pressures.size());
  EXPECT_NEAR(read.input(pe::input::Scalar::kStaticPressure)[5].value, sim.pressures[5].value, 0.01);
  EXPECT_FALSE(read.input(pe::input::Scalar::kAirTemperature).empty());
  std::size_t in_range = 0;
  for (const pe::sim::RangeSample& r : sim.ranges) in_range += r.range_m >= r.min_range_m && r.range_m <= r.max_range_m;
  EXPECT_EQ(read.input(pe::input::Scalar::kRangefinder).size(), in_range);
  ASSERT_EQ(read.input(pe::input::Scalar::kMotorTemperature).size(), sim.motor_temperatures.size());
  EXPECT_NEAR(read.input(pe::input::Scalar::kMotorTemperature).back().value, sim.motor_temperatures.back().value, 1e-4);
}

// The ESC telemetry a log reader read back against what the simulator emitted: one reading per
// packet, each motor's rotor speed (whole rpm in a ULog), voltage and current (floats).
inline void expectEscRoundTrip(const propulsion_estimator::FlightStreams& read, const RecordingFlightSink& sim) {
  ASSERT_FALSE(sim.escs.empty());
  ASSERT_EQ(read.esc.size(), sim.escs.size());
  for (std::size_t i = 0; i < sim.escs.size(); i += 5) {
    EXPECT_NEAR(read.esc[i].time_s, sim.escs[i].time_s, 1e-6) << i;
    ASSERT_EQ(read.esc[i].escs, static_cast<int>(sim.escs[i].escs.size())) << i;
    for (int k = 0; k < read.esc[i].escs; ++k) {
      EXPECT_NEAR(read.esc[i].rpm[k], sim.escs[i].escs[k].rpm, 0.5) << i;
      EXPECT_NEAR(read.esc[i].voltage_v[k], sim.escs[i].escs[k].voltage_v, 1e-5) << i;
      EXPECT_NEAR(read.esc[i].current_a[k], sim.escs[i].escs[k].current_a, 1e-5) << i;
    }
  }
}

#pragma once

#include <vector>

#include "propulsion_estimator/sim/flight/flight_sink.h"

// Keeps everything a simulated flight emits, for tests.
struct RecordingFlightSink : propulsion_estimator::sim::FlightSink {
  std::vector<propulsion_estimator::sim::RcOutSample> rc_out;
  std::vector<propulsion_estimator::sim::BatterySample> batteries;
  std::vector<propulsion_estimator::sim::ImuSample> imus;
  std::vector<propulsion_estimator::sim::PoseSample> poses;
  std::vector<propulsion_estimator::sim::VelocitySample> velocities;
  std::vector<propulsion_estimator::sim::ScalarSample> pressures;
  std::vector<propulsion_estimator::sim::ScalarSample> air_temperatures;
  std::vector<propulsion_estimator::sim::RangeSample> ranges;
  std::vector<propulsion_estimator::sim::ScalarSample> motor_temperatures;
  std::vector<propulsion_estimator::sim::TruthSample> truths;
  std::vector<propulsion_estimator::sim::EscTelemetrySample> escs;

  void rcOut(const propulsion_estimator::sim::RcOutSample& s) override { rc_out.push_back(s); }
  void battery(const propulsion_estimator::sim::BatterySample& s) override { batteries.push_back(s); }
  void imu(const propulsion_estimator::sim::ImuSample& s) override { imus.push_back(s); }
  void pose(const propulsion_estimator::sim::PoseSample& s) override { poses.push_back(s); }
  void velocity(const propulsion_estimator::sim::VelocitySample& s) override { velocities.push_back(s); }
  void staticPressure(const propulsion_estimator::sim::ScalarSample& s) override { pressures.push_back(s); }
  void airTemperature(const propulsion_estimator::sim::ScalarSample& s) override { air_temperatures.push_back(s); }
  void rangefinder(const propulsion_estimator::sim::RangeSample& s) override { ranges.push_back(s); }
  void motorTemperature(const propulsion_estimator::sim::ScalarSample& s) override { motor_temperatures.push_back(s); }
  void truth(const propulsion_estimator::sim::TruthSample& s) override { truths.push_back(s); }
  void escTelemetry(const propulsion_estimator::sim::EscTelemetrySample& s) override { escs.push_back(s); }
};

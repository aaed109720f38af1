#pragma once

#include <vector>

#include "propulsion_estimator/sim/flight/flight_sink.h"

// Keeps everything a simulated flight emits, for tests.
struct RecordingFlightSink : propulsion_estimator::FlightSink {
  std::vector<propulsion_estimator::RcOutSample> rc_out;
  std::vector<propulsion_estimator::BatterySample> batteries;
  std::vector<propulsion_estimator::ImuSample> imus;
  std::vector<propulsion_estimator::PoseSample> poses;
  std::vector<propulsion_estimator::VelocitySample> velocities;
  std::vector<propulsion_estimator::ScalarSample> pressures;
  std::vector<propulsion_estimator::ScalarSample> air_temperatures;
  std::vector<propulsion_estimator::RangeSample> ranges;
  std::vector<propulsion_estimator::ScalarSample> motor_temperatures;
  std::vector<propulsion_estimator::TruthSample> truths;

  void rcOut(const propulsion_estimator::RcOutSample& s) override { rc_out.push_back(s); }
  void battery(const propulsion_estimator::BatterySample& s) override { batteries.push_back(s); }
  void imu(const propulsion_estimator::ImuSample& s) override { imus.push_back(s); }
  void pose(const propulsion_estimator::PoseSample& s) override { poses.push_back(s); }
  void velocity(const propulsion_estimator::VelocitySample& s) override { velocities.push_back(s); }
  void staticPressure(const propulsion_estimator::ScalarSample& s) override { pressures.push_back(s); }
  void airTemperature(const propulsion_estimator::ScalarSample& s) override { air_temperatures.push_back(s); }
  void rangefinder(const propulsion_estimator::RangeSample& s) override { ranges.push_back(s); }
  void motorTemperature(const propulsion_estimator::ScalarSample& s) override { motor_temperatures.push_back(s); }
  void truth(const propulsion_estimator::TruthSample& s) override { truths.push_back(s); }
};

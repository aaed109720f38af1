// One preparation of the effects' signals: the node (Estimator::effectSignals) and the gap
// diagnosis (cutIntoBlocks) turn the same readings into the same height, current, air density and
// temperatures, so that a parameter fitted by the diagnosis means on the vehicle what it meant in
// the fit. Before, the diagnosis took the raw range (not range x cos(tilt)) and the current's sign
// from the flight's median, and the air density was computed in four places.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "estimator_fixture.h"
#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/model/effect_signals.h"

namespace gap = propulsion_estimator::gap;
namespace effects = propulsion_estimator::effects;

namespace {

// One instant's readings, as a log holds them and as the node receives them.
struct Readings {
  double current_a;  // either sign, as the autopilot reports it
  double roll_rad;
  double range_m;
  double pressure_pa;
  double air_temperature_c;
  double motor_temperature_c;
  double vertical_speed_m_s;
  double east_m_s;  // horizontal velocity (ENU)
  double north_m_s;
  Eigen::Quaterniond attitude() const { return Eigen::Quaterniond(Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX())); }
};

// The node's signals after receiving `r` at t = 100 s.
effects::Signals nodeSignals(const Readings& r) {
  EstimatorFixture fixture;
  pe::Estimator& estimator = fixture.estimator;
  const double t = 100.0;
  EXPECT_EQ(estimator.addBattery(t, 11.4), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addBatteryCurrent(t, r.current_a), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addImu(t, r.attitude(), Eigen::Vector3d(0.0, 0.0, pe::kStandardGravity)), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addRange(t, r.range_m, 0.1, 20.0), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addInput(pe::input::Scalar::kStaticPressure, t, r.pressure_pa), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addInput(pe::input::Scalar::kAirTemperature, t, r.air_temperature_c), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addInput(pe::input::Scalar::kMotorTemperature, t, r.motor_temperature_c), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addVerticalSpeed(t, r.vertical_speed_m_s), pe::Rejection::kNone);
  EXPECT_EQ(estimator.addHorizontalVelocity(t, r.east_m_s, r.north_m_s), pe::Rejection::kNone);
  return estimator.effectSignals(t);
}

// The diagnosis' signals of a 1 s block of a flight logging `r` throughout at 10 Hz.
gap::Block diagnosisBlock(const Readings& r) {
  pe::Flight flight;
  flight.name = "f.bag";
  flight.streams.motors = 4;
  for (int i = 0; i <= 30; ++i) {
    const double t = 0.1 * i;
    pe::RcOutFrame frame;
    frame.time_s = t;
    for (int k = 0; k < 4; ++k) frame.pwm_us[k] = 1500.0;
    flight.streams.rc_out.push_back(frame);
    flight.streams.battery.push_back({t, 11.4, r.current_a});
    pe::ImuReading imu;
    imu.time_s = t;
    imu.orientation = r.attitude();
    imu.specific_force_m_s2 = Eigen::Vector3d(0.0, 0.0, pe::kStandardGravity);
    flight.streams.imu.push_back(imu);
    flight.streams.input(pe::input::Scalar::kRangefinder).push_back({t, r.range_m});
    flight.streams.input(pe::input::Scalar::kStaticPressure).push_back({t, r.pressure_pa});
    flight.streams.input(pe::input::Scalar::kAirTemperature).push_back({t, r.air_temperature_c});
    flight.streams.input(pe::input::Scalar::kMotorTemperature).push_back({t, r.motor_temperature_c});
    flight.streams.vertical_speed_m_s.push_back({t, r.vertical_speed_m_s});
    flight.streams.horizontal_velocity.push_back({t, r.east_m_s, r.north_m_s});
  }
  flight.segments.push_back({1.0, 2.5, 1.3});
  gap::BlockConfig config;
  const gap::FlightBlocks cut = gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config, 0);
  EXPECT_FALSE(cut.blocks.empty());
  return cut.blocks.empty() ? gap::Block() : cut.blocks.front();
}

void expectSamePreparation(const Readings& r) {
  const effects::Signals node = nodeSignals(r);
  const gap::Block block = diagnosisBlock(r);
  const effects::Signals& fit = block.signals;
  EXPECT_NEAR(node.value(effects::Signal::kHeight), fit.value(effects::Signal::kHeight), 1e-9);
  EXPECT_NEAR(node.value(effects::Signal::kBatteryCurrent), fit.value(effects::Signal::kBatteryCurrent), 1e-9);
  EXPECT_NEAR(node.value(effects::Signal::kBatteryCurrent), block.current_a, 1e-9);
  EXPECT_NEAR(node.value(effects::Signal::kAirDensity), fit.value(effects::Signal::kAirDensity), 1e-12);
  EXPECT_NEAR(node.value(effects::Signal::kMotorTemperature), fit.value(effects::Signal::kMotorTemperature), 1e-12);
  EXPECT_NEAR(node.value(effects::Signal::kVerticalSpeed), fit.value(effects::Signal::kVerticalSpeed), 1e-12);
  EXPECT_NEAR(node.value(effects::Signal::kHorizontalSpeed), fit.value(effects::Signal::kHorizontalSpeed), 1e-12);
  EXPECT_NEAR(node.value(effects::Signal::kAxialSpeed), fit.value(effects::Signal::kAxialSpeed), 1e-12);
  // And what they are: the tilted range's vertical, the discharge, the dry air's density.
  EXPECT_NEAR(fit.value(effects::Signal::kHeight), r.range_m * std::cos(r.roll_rad), 1e-9);
  EXPECT_NEAR(fit.value(effects::Signal::kBatteryCurrent), std::fabs(r.current_a), 1e-9);
  EXPECT_NEAR(fit.value(effects::Signal::kAirDensity), effects::airDensityKgM3(r.pressure_pa, r.air_temperature_c), 1e-12);
  // The speed over the ground, and the velocity along the rolled body's z axis (0, -sin, cos).
  EXPECT_NEAR(fit.value(effects::Signal::kHorizontalSpeed), std::hypot(r.east_m_s, r.north_m_s), 1e-12);
  EXPECT_NEAR(fit.value(effects::Signal::kAxialSpeed),
              r.vertical_speed_m_s * std::cos(r.roll_rad) - r.north_m_s * std::sin(r.roll_rad), 1e-9);
}

}  // namespace

TEST(SignalPreparation, NodeAndDiagnosisAgreeOnAPx4FlightTilted) {
  // PX4 through MAVROS: discharge negative; 20 deg of roll in a manoeuvre, moving south-east.
  expectSamePreparation({-14.2, 0.35, 1.8, 88000.0, 31.0, 62.0, 0.4, 2.0, -3.0});
}

TEST(SignalPreparation, NodeAndDiagnosisAgreeOnAnArduPilotFlightLevel) {
  // ArduPilot: discharge positive; level, close to the ground, cold air.
  expectSamePreparation({9.7, 0.0, 0.35, 101800.0, -5.0, 18.0, -0.2, 0.0, 0.0});
}

TEST(SignalPreparation, TheFormulas) {
  EXPECT_NEAR(effects::airDensityKgM3(101325.0, 15.0), 1.225, 1e-3);
  EXPECT_TRUE(std::isnan(effects::airDensityKgM3(pe::kNaN, 15.0)));
  EXPECT_DOUBLE_EQ(effects::dischargeCurrentA(-12.5), 12.5);
  EXPECT_DOUBLE_EQ(effects::dischargeCurrentA(12.5), 12.5);
  EXPECT_TRUE(std::isnan(effects::dischargeCurrentA(pe::kNaN)));
  EXPECT_NEAR(effects::heightAboveGroundM(2.0, 0.5), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(effects::heightAboveGroundM(2.0, 0.0))) << "on its side the sensor sees no ground";
  EXPECT_TRUE(std::isnan(effects::heightAboveGroundM(2.0, -0.3)));
  EXPECT_EQ(effects::heightAboveGroundM(std::numeric_limits<double>::infinity(), 0.9), std::numeric_limits<double>::infinity()) << "nothing within reach: far";
  EXPECT_TRUE(std::isnan(effects::heightAboveGroundM(pe::kNaN, 1.0)));
  // Without the horizontal velocity the axial speed is the vertical speed's share along the axis.
  effects::RawSignals raw;
  raw.vertical_speed_m_s = 1.0;
  raw.body_z_up = 0.8;
  raw.body_z_east = 0.6;
  EXPECT_NEAR(effects::prepareSignals(raw).value(effects::Signal::kAxialSpeed), 0.8, 1e-12);
  EXPECT_TRUE(std::isnan(effects::prepareSignals(raw).value(effects::Signal::kHorizontalSpeed)));
  raw.velocity_east_m_s = 2.0;
  raw.velocity_north_m_s = 5.0;
  EXPECT_NEAR(effects::prepareSignals(raw).value(effects::Signal::kAxialSpeed), 0.8 + 1.2, 1e-12);
}

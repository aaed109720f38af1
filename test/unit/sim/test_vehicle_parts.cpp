// A vehicle's own parts (vehicle.parts): drawn per motor from the vehicle's seed, the same on every
// flight of the vehicle; none or spreads of 0 fly today's identical motors bit for bit; and
// propellers of one spin direction turning more torque per thrust move the yaw balance's thrust
// onto the other direction's diagonal pair, as on real Crazyflies.
#include <gtest/gtest.h>

#include <cmath>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/flight/vehicle_parts.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "recording_flight_sink.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::sim::VehicleParts messyParts(std::uint64_t seed) {
  pe::sim::VehicleParts parts;
  parts.seed = seed;
  parts.thrust_coefficient_spread = 0.03;
  parts.torque_coefficient_spread = 0.03;
  parts.kv_spread = 0.02;
  parts.esc_end_point_spread_us = 8.0;
  parts.spin_torque_ratio = 1.06;
  return parts;
}

// The default flight up to its first hover (at 2 m), then a landing: motors 1 and 2 (the
// front-right, rear-left diagonal) spin counter-clockwise, 3 and 4 clockwise.
pe::sim::FlightProfile shortProfile(std::optional<pe::sim::VehicleParts> parts) {
  pe::sim::FlightProfile profile = pe::sim::loadFlightProfileFile(repoPath("config/sim/default_flight.yaml"));
  profile.segments.resize(3);  // wait, take off, hover
  profile.segments.push_back({pe::sim::SegmentKind::kLand, 0.0, 0.0, 1.0, 0.0});
  profile.vehicle.parts = parts;
  return profile;
}

struct Flight {
  RecordingFlightSink sink;
  pe::sim::FlightResult result;
};

Flight fly(const pe::sim::FlightProfile& profile, std::uint64_t seed) {
  Flight flight;
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  flight.result = pe::sim::simulateFlight(pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")),
                                          {}, profile, vehicle, seed, &flight.sink);
  return flight;
}

// Every motor's true pulse width, thrust and speed at every sample, and the heights.
std::vector<double> trajectory(const Flight& flight) {
  std::vector<double> values;
  for (const pe::sim::TruthSample& t : flight.sink.truths) {
    values.push_back(t.height_m);
    for (const pe::sim::MotorTruth& m : t.motors) values.insert(values.end(), {m.pwm_us, m.thrust_n, m.rpm});
  }
  return values;
}

// Per motor, the mean true pulse width (us) and thrust (N) over the flight's first manifest
// segment (the settled hover).
struct HoverMeans {
  std::vector<double> pwm_us = std::vector<double>(4, 0.0);
  std::vector<double> thrust_n = std::vector<double>(4, 0.0);
};

HoverMeans hoverMeans(const Flight& flight) {
  HoverMeans means;
  const pe::ManifestSegment& hover = flight.result.segments.at(0);
  int n = 0;
  for (const pe::sim::TruthSample& t : flight.sink.truths) {
    if (t.time_s < hover.start_s || t.time_s > hover.end_s) continue;
    for (int k = 0; k < 4; ++k) {
      means.pwm_us[k] += t.motors[k].pwm_us;
      means.thrust_n[k] += t.motors[k].thrust_n;
    }
    ++n;
  }
  for (int k = 0; k < 4; ++k) {
    means.pwm_us[k] /= n;
    means.thrust_n[k] /= n;
  }
  return means;
}

const Flight& identicalMotorsFlight() {
  static const Flight flight = fly(shortProfile(std::nullopt), 4);
  return flight;
}

}  // namespace

TEST(VehicleParts, EachMotorDrawsItsOwnPartsFromTheVehiclesSeed) {
  const std::vector<int> spins = {1, 1, -1, -1};
  const std::vector<pe::sim::MotorParts> a = pe::sim::drawMotorParts(messyParts(7), spins);
  const std::vector<pe::sim::MotorParts> again = pe::sim::drawMotorParts(messyParts(7), spins);
  const std::vector<pe::sim::MotorParts> other = pe::sim::drawMotorParts(messyParts(8), spins);
  ASSERT_EQ(a.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(a[k].thrust_coefficient_factor, again[k].thrust_coefficient_factor);
    EXPECT_EQ(a[k].torque_coefficient_factor, again[k].torque_coefficient_factor);
    EXPECT_EQ(a[k].kv_factor, again[k].kv_factor);
    EXPECT_EQ(a[k].esc_end_point_shift_us, again[k].esc_end_point_shift_us);
    EXPECT_NE(a[k].thrust_coefficient_factor, other[k].thrust_coefficient_factor);
    // Within the clip of 2 sigma; the spin direction's share of the torque on top.
    EXPECT_LE(std::fabs(a[k].thrust_coefficient_factor - 1.0), 0.06 + 1e-12);
    EXPECT_LE(std::fabs(a[k].kv_factor - 1.0), 0.04 + 1e-12);
    EXPECT_LE(std::fabs(a[k].esc_end_point_shift_us), 16.0 + 1e-12);
    const double share = spins[k] > 0 ? 1.0 / std::sqrt(1.06) : std::sqrt(1.06);
    EXPECT_LE(std::fabs(a[k].torque_coefficient_factor / share - 1.0), 0.06 + 1e-12);
  }
  // The parts differ from motor to motor, and each draw is its own.
  for (int k = 1; k < 4; ++k) {
    EXPECT_NE(a[k].thrust_coefficient_factor, a[0].thrust_coefficient_factor);
    EXPECT_NE(a[k].kv_factor, a[0].kv_factor);
    EXPECT_NE(a[k].esc_end_point_shift_us, a[0].esc_end_point_shift_us);
  }
  EXPECT_NE(a[0].thrust_coefficient_factor, a[0].torque_coefficient_factor * std::sqrt(1.06));
  // A spread of 0 leaves the other parts as drawn.
  pe::sim::VehicleParts exact_kv = messyParts(7);
  exact_kv.kv_spread = 0.0;
  const std::vector<pe::sim::MotorParts> b = pe::sim::drawMotorParts(exact_kv, spins);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(b[k].kv_factor, 1.0);
    EXPECT_EQ(b[k].thrust_coefficient_factor, a[k].thrust_coefficient_factor);
    EXPECT_EQ(b[k].esc_end_point_shift_us, a[k].esc_end_point_shift_us);
  }
}

TEST(VehicleParts, APartsChainScalesItsCoefficientsAndShiftsBothEndPoints) {
  const pe::sim::ChainParams chain = pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")).chain;
  const pe::sim::ChainParams parted = pe::sim::withParts(chain, {1.02, 0.97, 1.01, -6.0});
  EXPECT_DOUBLE_EQ(parted.propeller.thrust_coefficient, 1.02 * chain.propeller.thrust_coefficient);
  EXPECT_DOUBLE_EQ(parted.propeller.torque_coefficient, 0.97 * chain.propeller.torque_coefficient);
  EXPECT_DOUBLE_EQ(parted.motor.kv_rpm_per_v, 1.01 * chain.motor.kv_rpm_per_v);
  EXPECT_DOUBLE_EQ(parted.esc.pwm_zero_us, chain.esc.pwm_zero_us - 6.0);
  EXPECT_DOUBLE_EQ(parted.esc.pwm_full_us, chain.esc.pwm_full_us - 6.0);
  EXPECT_EQ(parted.propeller.diameter_m, chain.propeller.diameter_m);
  EXPECT_EQ(parted.motor.winding_resistance_ohm, chain.motor.winding_resistance_ohm);
}

TEST(VehicleParts, SpreadsOfZeroFlyTodaysIdenticalMotorsBitForBit) {
  pe::sim::VehicleParts none;
  none.seed = 7;
  const Flight zero = fly(shortProfile(none), 4);
  EXPECT_EQ(trajectory(zero), trajectory(identicalMotorsFlight()));
  ASSERT_EQ(zero.sink.imus.size(), identicalMotorsFlight().sink.imus.size());
  for (std::size_t i = 0; i < zero.sink.imus.size(); ++i) {
    ASSERT_EQ(zero.sink.imus[i].linear_acceleration_m_s2, identicalMotorsFlight().sink.imus[i].linear_acceleration_m_s2);
  }
}

TEST(VehicleParts, EveryFlightOfTheVehicleFliesItsOwnParts) {
  // Another flight seed (another day's sensor noise): the same parts, so the same true flight;
  // another vehicle (parts seed): other parts, another flight.
  const Flight a = fly(shortProfile(messyParts(7)), 4);
  const Flight b = fly(shortProfile(messyParts(7)), 5);
  const Flight c = fly(shortProfile(messyParts(8)), 4);
  EXPECT_EQ(trajectory(a), trajectory(b));
  EXPECT_NE(trajectory(a), trajectory(c));
  EXPECT_NE(trajectory(a), trajectory(identicalMotorsFlight()));
  // The parts show in the hover: the pulse widths move from the identical motors', on average
  // by more than 3 us.
  const HoverMeans parted = hoverMeans(a);
  const HoverMeans identical = hoverMeans(identicalMotorsFlight());
  double moved = 0.0;
  for (int k = 0; k < 4; ++k) moved += std::fabs(parted.pwm_us[k] - identical.pwm_us[k]);
  EXPECT_GT(moved, 4 * 3.0);
}

TEST(VehicleParts, PropellersOfOneSpinDirectionTurningMoreTorqueShiftTheThrustToTheOtherDiagonal) {
  // Clockwise propellers (motors 3 and 4) turning 6 % more torque per thrust than the
  // counter-clockwise ones: the yaw balance needs sqrt(1.06)^2 = 1.06 x the thrust on the
  // counter-clockwise diagonal (51.5 % of the total against 48.5 %), which it gets at a higher
  // pulse width.
  pe::sim::VehicleParts mirror_broken;
  mirror_broken.seed = 7;
  mirror_broken.spin_torque_ratio = 1.06;
  const HoverMeans hover = hoverMeans(fly(shortProfile(mirror_broken), 4));
  const HoverMeans identical = hoverMeans(identicalMotorsFlight());
  const double ccw = hover.thrust_n[0] + hover.thrust_n[1], cw = hover.thrust_n[2] + hover.thrust_n[3];
  EXPECT_NEAR(ccw / cw, 1.06, 0.005);
  EXPECT_NEAR(100.0 * (ccw - cw) / (ccw + cw), 2.9, 0.3);  // points of the summed thrust
  const double ccw_pwm = 0.5 * (hover.pwm_us[0] + hover.pwm_us[1]), cw_pwm = 0.5 * (hover.pwm_us[2] + hover.pwm_us[3]);
  const double identical_gap =
      0.5 * (identical.pwm_us[0] + identical.pwm_us[1]) - 0.5 * (identical.pwm_us[2] + identical.pwm_us[3]);
  EXPECT_NEAR(identical_gap, 0.0, 1.0);
  EXPECT_GT(ccw_pwm, cw_pwm + 5.0);  // measured 2026-11-28: 1641.2 us against 1627.6 us
}

TEST(VehicleParts, RefusesDrawnPartsItsChainCannotBeNamingTheMotor) {
  // A torque spread of 10 % with the ratio's share on top takes some propeller's torque below the
  // induced torque of its thrust for some seed.
  pe::sim::VehicleParts extreme = messyParts(0);
  extreme.thrust_coefficient_spread = 0.1;
  extreme.torque_coefficient_spread = 0.1;
  extreme.spin_torque_ratio = 0.8;
  const pe::sim::SimParams params = pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  std::string message;
  for (std::uint64_t seed = 0; seed < 100 && message.empty(); ++seed) {
    extreme.seed = seed;
    try {
      pe::sim::checkFlight(params, {}, shortProfile(extreme), vehicle);
    } catch (const pe::ConfigError& e) {
      message = e.what();
    }
  }
  EXPECT_NE(message.find(repoPath("config/sim/default_flight.yaml") + ": vehicle.parts: motor "), std::string::npos)
      << message;
  EXPECT_NE(message.find("'s drawn propeller.torque_coefficient: "), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

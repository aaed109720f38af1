// Its own test binary: it replaces the global operator new to count allocations. What the node
// does per RCOut message besides roscpp's own (de)serialization: decode, then estimate.
#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "estimator_fixture.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/onboard/model_check.h"
#include "propulsion_estimator/onboard/rpm_mass_view.h"
#include "propulsion_estimator/codecs/esc_telemetry_codec.h"
#include "propulsion_estimator/sim/flight/motor_mixer.h"
#include "propulsion_estimator/codecs/rcout_codec.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

TEST(Estimator, EvaluatesMotorOutputsWithoutHeapAllocation) {
  EstimatorFixture f;
  f.fly(1690.0, 20.0);  // windows full, everything warmed up
  const std::vector<std::uint16_t> channels{1690, 1700, 1680, 1695, 1000, 1000, 1000, 1000};
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  const long before = g_allocations.load();
  for (int k = 0; k < 1000; ++k, f.t += 0.02) {
    f.estimator.addImu(f.t, level, Eigen::Vector3d(0, 0, 9.81));
    f.estimator.addVerticalSpeed(f.t, 0.1);
    if (k % 50 == 0) f.estimator.addBattery(f.t, 11.4);
    ASSERT_EQ(f.estimator.addMotorOutputs(f.t, f.t, channels.data(), channels.size()), pe::Rejection::kNone);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_TRUE(f.estimator.output().hover.hovering);
}

TEST(Estimator, AppliesEveryEffectWithoutHeapAllocation) {
  pe::effects::ModelEffects effects;
  effects.setParameter(pe::effects::Kind::kEscOffset, 10.0);
  effects.setParameter(pe::effects::Kind::kSupplyResistance, 0.04);
  effects.setParameter(pe::effects::Kind::kAirDensity, 0.9);
  effects.setParameter(pe::effects::Kind::kGroundEffect, 0.001);
  effects.rotor_height_m = 0.1;
  effects.setParameter(pe::effects::Kind::kThrustLoss, 0.03);
  effects.setParameter(pe::effects::Kind::kMotorTemperature, 0.001);
  effects.motor_reference_c = 22.0;
  effects.setParameter(pe::effects::Kind::kClimbInflow, 0.03);
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), effects);
  f.fly(1690.0, 20.0);
  const std::vector<std::uint16_t> channels{1690, 1700, 1680, 1695, 1000, 1000, 1000, 1000};
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  const long before = g_allocations.load();
  for (int k = 0; k < 1000; ++k, f.t += 0.02) {
    f.estimator.addImu(f.t, level, Eigen::Vector3d(0, 0, 9.81));
    f.estimator.addVerticalSpeed(f.t, 0.1);
    f.estimator.addRange(f.t, 2.0, 0.1, 12.0);
    f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 98000.0);
    if (k % 50 == 0) {
      f.estimator.addBattery(f.t, 11.4);
      f.estimator.addBatteryCurrent(f.t, -17.0);
      f.estimator.addInput(pe::input::Scalar::kAirTemperature, f.t, 24.0);
      f.estimator.addInput(pe::input::Scalar::kMotorTemperature, f.t, 45.0);
    }
    ASSERT_EQ(f.estimator.addMotorOutputs(f.t, f.t, channels.data(), channels.size()), pe::Rejection::kNone);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(f.estimator.output().effects_skipped, 0u);
  EXPECT_TRUE(f.estimator.output().hover.hovering);
}

TEST(MotorHealth, TakesEachEstimateWithoutHeapAllocation) {
  EstimatorFixture f;
  pe::MotorHealth health(pe::Vehicle::quadX(0.225), {1, 2, 3, 4}, {});
  f.fly(1690.0, 20.0);
  const std::vector<std::uint16_t> channels{1690, 1700, 1680, 1695};
  const long before = g_allocations.load();
  for (int k = 0; k < 1000; ++k, f.t += 0.02) {
    if (k % 50 == 0) f.estimator.addBattery(f.t, 11.4);
    ASSERT_EQ(f.estimator.addMotorOutputs(f.t, f.t, channels.data(), channels.size()), pe::Rejection::kNone);
    health.add(f.estimator.output());
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_TRUE(health.verdict().judged);
}

TEST(RcOutDecoder, DecodesWithoutHeapAllocationOnceWarm) {
  pe::RcOutMessage sent;
  sent.header.frame_id = "a_frame_id_longer_than_the_small_string_buffer";
  sent.channels.assign(16, 1500);
  const topic_tools::ShapeShifter shifter = pe::encodeRcOut(sent);
  pe::RcOutDecoder decoder;
  pe::RcOutMessage received;
  std::string error;
  ASSERT_TRUE(decoder.decode(shifter, &received, &error));
  const long before = g_allocations.load();
  for (int k = 0; k < 1000; ++k) ASSERT_TRUE(decoder.decode(shifter, &received, &error));
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(received.header.frame_id, sent.header.frame_id);
  EXPECT_EQ(received.channels, sent.channels);
}

TEST(EscTelemetryDecoder, DecodesWithoutHeapAllocationOnceWarm) {
  for (const bool px4 : {false, true}) {
    pe::EscTelemetry sent;
    sent.stamp_s = 12.5;
    for (int k = 0; k < 8; ++k) sent.escs.push_back({12.5, 6000.0 + k, 5.0, 16.0, 30.0, 7});
    const topic_tools::ShapeShifter shifter = pe::encodeEscTelemetry(sent, px4);
    pe::EscTelemetryDecoder decoder;
    pe::EscTelemetry received;
    std::string error;
    ASSERT_TRUE(decoder.decode(shifter, &received, &error)) << error;
    const long before = g_allocations.load();
    for (int k = 0; k < 1000; ++k) ASSERT_TRUE(decoder.decode(shifter, &received, &error));
    EXPECT_EQ(g_allocations.load() - before, 0) << (px4 ? "ESCStatus" : "ESCTelemetry");
    ASSERT_EQ(received.escs.size(), sent.escs.size());
    EXPECT_EQ(received.escs[7].rpm, 6007.0);
  }
}

TEST(ModelCheck, TakesTelemetryEstimatesAndBatteryWithoutHeapAllocation) {
  EstimatorFixture f;
  f.fly(1690.0, 20.0);
  const std::vector<std::uint16_t> channels{1690, 1700, 1680, 1695};
  pe::ModelCheck check({1, 2, 3, 4}, {});
  pe::RpmMassView view(pe::RpmThrust{1.6e-7, 0.0, pe::kNaN, pe::kNaN}, 10.0);
  pe::EscTelemetry message;
  message.escs.assign(4, {0.0, 6000.0, 5.0, 16.0, 30.0, 0});
  const auto step = [&](int k) {
    ASSERT_EQ(f.estimator.addMotorOutputs(f.t, f.t, channels.data(), channels.size()), pe::Rejection::kNone);
    check.addEstimate(f.t, f.estimator.output());
    view.add(f.t, f.estimator.output(), check, pe::kNaN);
    if (k % 5 == 0) {
      message.stamp_s = f.t;
      for (pe::EscReport& esc : message.escs) esc.count = k;
      check.addTelemetry(f.t, message);
    }
    if (k % 50 == 0) {
      f.estimator.addBattery(f.t, 11.4);
      check.addBattery(f.t, 11.4);
    }
  };
  int k = 0;
  for (; k < 1000; ++k, f.t += 0.02) step(k);  // warm: windows full
  const long before = g_allocations.load();
  for (; k < 2000; ++k, f.t += 0.02) step(k);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(check.report(f.t).fresh_motors, 4);
  EXPECT_GT(view.hoverS(), 0.0);
}

TEST(MotorMixer, MixesWithoutHeapAllocation) {
  // The flight simulator mixes every 2 ms step.
  pe::sim::MotorMixer mixer(pe::Vehicle::quadX(0.225));
  const long before = g_allocations.load();
  double sum = 0.0;
  for (int k = 0; k < 1000; ++k) sum += mixer.mix(0.5, 0.01 * (k % 7), -0.02, 0.005).front();
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(sum, 0.0);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

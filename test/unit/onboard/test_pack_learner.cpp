// A pack learned from one flight: its rest voltages, the charge drawn, its loaded curve and its
// resistance; the curve a record gives over 0..1; the node's pack file across a run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "propulsion_estimator/onboard/battery_estimator.h"
#include "propulsion_estimator/onboard/pack_file_keeper.h"
#include "propulsion_estimator/onboard/pack_learner.h"

namespace pe = propulsion_estimator;

namespace {

pe::PackLearnerConfig threeCellLearner() {
  pe::PackLearnerConfig config;
  config.cells = 3;
  config.capacity_ah = 4.0;
  return config;
}

// A pack on the built-in LiPo curve with 30 mOhm, 3.6 Ah: 20 s at rest at `start_soc`, a hover at
// 14 A for `hover_s`, 30 s at rest; fed to `learner` with a resistance identified at 30 mOhm.
void flyPack(pe::PackLearner* learner, double start_soc, double hover_s, double t0 = 0.0) {
  const pe::OcvCurve curve = pe::OcvCurve::lipo();
  pe::BatteryEstimate estimate;
  estimate.internal_resistance_ohm = 0.03;
  estimate.current_span_a = 14.0;
  double soc = start_soc, t = t0;
  const auto reading = [&](double current_a) {
    soc -= current_a / (3600.0 * 3.6);
    learner->add(t, 3.0 * curve.cellVoltage(soc) - 0.03 * current_a, current_a, estimate);
    t += 1.0;
  };
  for (int k = 0; k < 20; ++k) reading(0.5);
  for (int k = 0; k < hover_s; ++k) reading(14.0);
  for (int k = 0; k < 30; ++k) reading(0.5);
}

pe::PackRecord freshRecord() {
  pe::PackRecord record;
  record.pack_id = "p";
  record.cells = 3;
  return record;
}

}  // namespace

TEST(PackLearner, LearnsTheCapacityCurveAndResistanceOfAFlight) {
  pe::PackLearner learner(threeCellLearner());
  flyPack(&learner, 0.95, 700.0);  // 2.7 Ah of 3.6: 0.95 to 0.20
  ASSERT_TRUE(learner.flightFinished());
  const pe::PackRecord record = learner.learned(freshRecord(), pe::OcvCurve::lipo());
  EXPECT_EQ(record.flights, 1);
  ASSERT_TRUE(record.capacity_ah.has_value());
  EXPECT_NEAR(*record.capacity_ah, 3.6, 0.05);
  ASSERT_EQ(record.resistance_ohm.size(), 1u);
  EXPECT_NEAR(record.resistance_ohm[0], 0.03, 1e-9);
  ASSERT_GE(record.ocv_soc.size(), 20u);
  for (std::size_t k = 0; k < record.ocv_soc.size(); ++k) {
    EXPECT_NEAR(record.ocv_cell_v[k], pe::OcvCurve::lipo().cellVoltage(record.ocv_soc[k]), 0.02) << record.ocv_soc[k];
  }
  EXPECT_GT(record.ocv_soc.front(), 0.15);
  EXPECT_LT(record.ocv_soc.back(), 0.95);
  // The next flight is learned on top: one more flight, the curve kept where this one did not fly.
  learner.startNextFlight();
  EXPECT_FALSE(learner.flightFinished());
  flyPack(&learner, 0.55, 200.0, 2000.0);
  const pe::PackRecord second = learner.learned(record, pe::OcvCurve::lipo());
  EXPECT_EQ(second.flights, 2);
  EXPECT_EQ(second.resistance_ohm.size(), 2u);
  EXPECT_GT(second.ocv_soc.back(), 0.85);  // the first flight's points above 0.55 stay
  for (std::size_t k = 1; k < second.ocv_soc.size(); ++k) {
    EXPECT_GT(second.ocv_soc[k], second.ocv_soc[k - 1]);
    EXPECT_GT(second.ocv_cell_v[k], second.ocv_cell_v[k - 1]);
  }
}

// A flight whose start was not seen at rest (the node started in the air) teaches nothing, nor
// does a flight not yet landed and settled.
TEST(PackLearner, LearnsNothingFromAFlightItDidNotSeeStartOrEnd) {
  pe::PackLearner learner(threeCellLearner());
  pe::BatteryEstimate estimate;
  estimate.internal_resistance_ohm = 0.03;
  estimate.current_span_a = 14.0;
  for (int t = 0; t < 300; ++t) learner.add(t, 11.5, 14.0, estimate);
  for (int t = 300; t < 340; ++t) learner.add(t, 11.9, 0.5, estimate);
  EXPECT_FALSE(learner.flightFinished());
  pe::PackLearner landing(threeCellLearner());
  for (int t = 0; t < 10; ++t) landing.add(t, 12.4, 0.5, estimate);
  for (int t = 10; t < 300; ++t) landing.add(t, 11.9, 14.0, estimate);
  for (int t = 300; t < 305; ++t) landing.add(t, 11.9, 0.5, estimate);  // settling, not yet 10 s
  EXPECT_FALSE(landing.flightFinished());
  EXPECT_DOUBLE_EQ(landing.restLeftS(), 6.0);  // at rest since 300 s, last reading at 304 s
  EXPECT_TRUE(std::isnan(learner.restLeftS())) << "a flight whose start was not seen awaits nothing";
  const pe::PackRecord unchanged = landing.learned(freshRecord(), pe::OcvCurve::lipo());
  EXPECT_EQ(unchanged.flights, 0);
}

// The record's curve over 0..1: its points, and the fallback beyond shifted to meet them.
TEST(PackLearner, TheLearnedCurveRunsFromEmptyToFullThroughItsPoints) {
  pe::PackRecord record = freshRecord();
  EXPECT_DOUBLE_EQ(pe::learnedCurve(record, pe::OcvCurve::lipo()).cellVoltage(0.5), pe::OcvCurve::lipo().cellVoltage(0.5));
  record.ocv_soc = {0.3, 0.5, 0.7};
  record.ocv_cell_v = {3.70, 3.78, 3.90};
  const pe::OcvCurve curve = pe::learnedCurve(record, pe::OcvCurve::lipo());
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(curve.cellVoltage(record.ocv_soc[k]), record.ocv_cell_v[k], 1e-12);
  EXPECT_DOUBLE_EQ(curve.socTable().front(), 0.0);
  EXPECT_DOUBLE_EQ(curve.socTable().back(), 1.0);
  // Beyond the points: the LiPo curve's shape, shifted to meet them.
  EXPECT_NEAR(curve.cellVoltage(0.9) - curve.cellVoltage(0.8), 4.11 - 4.02, 1e-9);
  EXPECT_NEAR(curve.cellVoltage(0.1), 3.69 + (3.70 - 3.77), 1e-9);
}

// The node's file across a run: absent, then written after a flight, read by the next run; a file
// of another pack is neither used nor written; a file that is not a pack record is moved aside.
TEST(PackFileKeeper, ReadsWritesAndNeverTouchesAnotherPack) {
  namespace fs = std::filesystem;
  const std::string folder = testing::TempDir() + "/pe_pack_keeper";
  fs::remove_all(folder);
  const std::string pattern = folder + "/{pack_id}.yaml";
  pe::PackFileKeeper off("", 3);
  EXPECT_FALSE(off.enabled());
  EXPECT_FALSE(off.identify("A", 0).has_value());

  pe::PackFileKeeper first(pattern, 3);
  EXPECT_FALSE(first.identify("A", 0).has_value());
  EXPECT_TRUE(first.active());
  pe::PackLearner learner(threeCellLearner());
  flyPack(&learner, 0.95, 700.0);
  const std::string line = first.save(learner.learned(first.previous(), pe::OcvCurve::lipo()));
  EXPECT_EQ(line.rfind(folder + "/A.yaml: pack \"A\", 1 flights learned, capacity 3.", 0), 0u) << line;

  pe::PackFileKeeper next(pattern, 3);
  const std::optional<pe::PackRecord> read = next.identify("A", 0);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->flights, 1);
  EXPECT_FALSE(next.identify("B", 0).has_value());  // another pack: its own file, none yet
  EXPECT_EQ(next.path(), folder + "/B.yaml");
  EXPECT_EQ(next.note(), folder + "/B.yaml: none yet for pack \"B\": learned from this flight");

  pe::PackFileKeeper single(folder + "/A.yaml", 3);
  EXPECT_FALSE(single.identify("B", 0).has_value());
  EXPECT_FALSE(single.active());
  EXPECT_EQ(single.save(first.previous()).rfind(folder + "/A.yaml: not written (", 0), 0u);
  EXPECT_EQ(pe::loadPackFile(folder + "/A.yaml")->pack_id, "A");

  std::ofstream(folder + "/C.yaml") << "pack_id: C\ncells: 3\n";
  pe::PackFileKeeper bad(pattern, 3);
  EXPECT_FALSE(bad.identify("C", 1700000000).has_value());
  EXPECT_TRUE(bad.active());
  EXPECT_NE(bad.note().find("moved to " + folder + "/C.yaml.bad-1700000000, learned afresh"), std::string::npos)
      << bad.note();
  EXPECT_TRUE(fs::exists(folder + "/C.yaml.bad-1700000000"));
  EXPECT_TRUE(bad.refused()) << "moved aside and learned afresh, but said as a warning";
  EXPECT_FALSE(next.refused());
  // A folder where the pack's file goes: refused by name, never written.
  fs::create_directories(folder + "/D.yaml");
  pe::PackFileKeeper in_the_way(pattern, 3);
  EXPECT_FALSE(in_the_way.identify("D", 0).has_value());
  EXPECT_TRUE(in_the_way.refused());
  EXPECT_FALSE(in_the_way.active());
  EXPECT_EQ(in_the_way.note(), "refused: " + folder + "/D.yaml: a folder, not a file; not written");
  fs::remove_all(folder);
}

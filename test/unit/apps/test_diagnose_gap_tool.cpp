// diagnose_gap run as a user runs it (the built executable) on bags written here: the flights it
// can use are read, each one it cannot is refused with one line, and the exit status says so.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <sensor_msgs/BatteryState.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>

#include "propulsion_estimator/bag/bag_flight_sink.h"
#include "propulsion_estimator/model/effect_description.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/codecs/rcout_codec.h"
#include "test_paths.h"
#include "tool_process.h"

namespace pe = propulsion_estimator;
namespace fs = std::filesystem;

namespace {

// rc/out at 10 Hz and the battery at 1 Hz for `duration_s`, on `battery_topic`.
void writeFlightBag(const std::string& path, double duration_s, const std::string& battery_topic = pe::kBatteryTopic) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  const ros::Time start(1600000000);
  pe::RcOutMessage rc_out;
  rc_out.channels = {1600, 1610, 1620, 1630, 900, 900, 0, 0};
  for (int i = 0; i <= static_cast<int>(duration_s * 10); ++i) {
    bag.write(pe::kRcOutTopic, start + ros::Duration(0.1 * i), pe::encodeRcOut(rc_out));
    if (i % 10 != 0) continue;
    sensor_msgs::BatteryState battery;
    battery.voltage = 12.0f;
    bag.write(battery_topic, start + ros::Duration(0.1 * i), battery);
  }
}

class DiagnoseGapTool : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pe_diagnose_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  ToolRun run(const std::string& arguments) const { return runTool(PE_DIAGNOSE_GAP, arguments, dir_); }

  // The required options for `manifest`, and `more`.
  ToolRun diagnose(const std::string& manifest, const std::string& more = "") const {
    return run("--model " + repoPath("config/e300_dji2212_dji9443.yaml") + " --manifest " + file(manifest) +
               " --out " + file("report") + " --python /usr/bin/python3 " + more);
  }

  void writeManifest(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }

  fs::path dir_;
};

// What the tool says about the flights it read, without the time it took.
std::string readLines(const std::string& out) {
  std::string lines;
  std::istringstream stream(out);
  for (std::string line; std::getline(stream, line);) {
    if (line.rfind("read ", 0) == 0) lines += line.substr(0, line.find(" in ")) + "\n";
  }
  return lines;
}

}  // namespace

TEST_F(DiagnoseGapTool, ListsTheEffectsOfTheRegistry) {
  const ToolRun listed = run("--list-effects");
  ASSERT_EQ(listed.status, 0) << listed.err;
  std::string expected;
  for (const std::string& name : pe::effects::allNames()) expected += name + "\n";
  EXPECT_EQ(listed.out, expected);
}

TEST_F(DiagnoseGapTool, ReadsEveryFlightInManifestOrderWhateverTheJobs) {
  writeFlightBag(file("a.bag"), 10.0);
  writeFlightBag(file("b.bag"), 20.0);
  writeManifest("m.yaml",
                "flights:\n"
                "  - bag: a.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n"
                "  - bag: b.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n"
                "      - {start: 10, end: 19.5, mass_kg: 1.711}\n");
  const ToolRun one = diagnose("m.yaml", "--jobs 1");
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(one.err, "");
  EXPECT_EQ(readLines(one.out),
            "read " + file("a.bag") +
                ": rc_out 101, battery 11, no imu, no pose, no velocity, no static_pressure, no air_temperature, no "
                "rangefinder, no motor_temperature, no esc_telemetry, no esc_status\n"
                "read " + file("b.bag") +
                ": rc_out 201, battery 21, no imu, no pose, no velocity, no static_pressure, no air_temperature, no "
                "rangefinder, no motor_temperature, no esc_telemetry, no esc_status\n"
                "read 2 of 2 flights, 334 readings,\n");
  EXPECT_NE(one.out.find("note: no --urdf or --frame: 4 motors on RCOut channels 1-4"), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("report: " + file("report") + "/report.md, corrected model: " + file("report") +
                         "/corrected_model.yaml\n"),
            std::string::npos)
      << one.out;
  for (const char* written : {"report.md", "report.yaml", "gap_samples.csv", "gap_signals.png", "corrected_model.yaml"}) {
    EXPECT_TRUE(fs::exists(dir_ / "report" / written)) << written;
  }
  // The corrected model is a model file the node loads: the input model, plus the effects selected.
  EXPECT_NO_THROW(pe::loadModelFile(file("report/corrected_model.yaml")));
  const ToolRun two = diagnose("m.yaml", "--jobs 2 --urdf " + repoPath("config/f450_quad.urdf"));
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_EQ(readLines(two.out), readLines(one.out));
  EXPECT_EQ(two.out.find("note:"), std::string::npos) << two.out;
}

TEST_F(DiagnoseGapTool, AcceptsASegmentThatEndsWhereTheLogEndsAsPrinted) {
  // The log ends at 9.9996 s, printed 10.000 s: a segment to 10 s is the log's span as the user
  // reads it; one to 10.002 s is not.
  writeFlightBag(file("a.bag"), 9.9);
  {
    rosbag::Bag bag(file("a.bag"), rosbag::bagmode::Append);
    pe::RcOutMessage rc_out;
    rc_out.channels = {1600, 1610, 1620, 1630, 900, 900, 0, 0};
    bag.write(pe::kRcOutTopic, ros::Time(1600000000) + ros::Duration(9.9996), pe::encodeRcOut(rc_out));
  }
  writeManifest("m.yaml", "flights:\n  - bag: a.bag\n    segments:\n      - {start: 0, end: 10, mass_kg: 1.315}\n");
  const ToolRun whole = diagnose("m.yaml");
  EXPECT_EQ(whole.err.find("is outside"), std::string::npos) << whole.err;
  writeManifest("m.yaml", "flights:\n  - bag: a.bag\n    segments:\n      - {start: 0, end: 10.002, mass_kg: 1.315}\n");
  const ToolRun beyond = diagnose("m.yaml");
  EXPECT_EQ(beyond.err, "diagnose_gap: " + file("m.yaml") + ": flights[0].segments[0]: 0..10.002 s is outside " +
                            file("a.bag") + " (0..10.000 s)\n"
                            "diagnose_gap: 1 of 1 flights refused\n");
}

TEST_F(DiagnoseGapTool, GoesOnWithTheFlightsItCanUse) {
  writeFlightBag(file("a.bag"), 10.0);
  writeFlightBag(file("no_battery.bag"), 10.0, "/power");
  writeManifest("m.yaml",
                "flights:\n"
                "  - bag: a.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n"
                "  - bag: missing.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n"
                "  - bag: no_battery.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n"
                "  - bag: a.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n"
                "      - {start: 9, end: 12.5, mass_kg: 1.315}\n"
                "  - bag: a.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 0}\n");
  for (const char* jobs : {"1", "3"}) {
    const ToolRun r = diagnose("m.yaml", std::string("--jobs ") + jobs);
    EXPECT_EQ(r.status, 1);
    const std::string m = file("m.yaml");
    EXPECT_EQ(r.err, "diagnose_gap: " + m + ": flights[1]: " + file("missing.bag") + ": no such file\n" +
                         "diagnose_gap: " + m + ": flights[2]: " + file("no_battery.bag") +
                         ": /mavros/battery: no messages (a required topic)\n" +
                         "diagnose_gap: " + m + ": flights[3].segments[1]: 9..12.5 s is outside " + file("a.bag") +
                         " (0..10.000 s)\n" +
                         "diagnose_gap: " + m +
                         ":17: flights[4].segments[0].mass_kg: 0 is outside 0..100 kg (must be positive)\n" +
                         "diagnose_gap: 4 of 5 flights refused\n");
    EXPECT_NE(r.out.find("read 1 of 5 flights, 112 readings, in "), std::string::npos) << r.out;
    // The flight it could use is diagnosed, and the report lists those it could not.
    const std::string report = slurp(dir_ / "report" / "report.md");
    EXPECT_NE(report.find("- " + m + ": flights[1]: " + file("missing.bag") + ": no such file\n"), std::string::npos)
        << report;
  }
  // The battery on another topic.
  writeManifest("other.yaml", "flights:\n  - bag: no_battery.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.3}\n");
  const ToolRun renamed = diagnose("other.yaml", "--topic battery=/power");
  EXPECT_EQ(renamed.status, 0) << renamed.err;
  EXPECT_NE(renamed.out.find("read 1 of 1 flights, 112 readings"), std::string::npos) << renamed.out;
}

// The demo bag with a chunk corrupt half-way: the flight is read up to there, the segments before
// it are diagnosed, and the one beyond says that the log breaks off there, not merely that the
// segment lies outside it.
TEST_F(DiagnoseGapTool, SaysASegmentBeyondADamagedLogsBreakLiesThere) {
  std::string bag = slurp(repoPath("config/demo/demo_flight.bag"));
  ASSERT_GT(bag.size(), 1000000u);
  bag.replace(bag.size() * 3 / 4, 64, std::string(64, '\xff'));
  std::ofstream(file("damaged.bag"), std::ios::binary) << bag;
  writeManifest("m.yaml",
                "flights:\n  - bag: damaged.bag\n    segments:\n      - {start: 11.88, end: 32.88, mass_kg: 1.315}\n"
                "      - {start: 93.4, end: 114.4, mass_kg: 1.711}\n");
  const ToolRun r = diagnose("m.yaml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("diagnose_gap: " + file("damaged.bag") + ": reading failed after "), std::string::npos) << r.err;
  const std::string report = slurp(dir_ / "report" / "report.md");
  EXPECT_TRUE(std::regex_search(report, std::regex("\n- damaged\\.bag: segment 2 \\(93\\.4-114\\.4 s\\) lies outside the "
                                                   "log's rc/out span 0\\.00-[0-9]+\\.[0-9]{2} s \\(the log is damaged "
                                                   "and read only up to there\\); skipped\n")))
      << report;
}

TEST_F(DiagnoseGapTool, RefusesBadArgumentsWithOneLine) {
  writeFlightBag(file("a.bag"), 10.0);
  writeManifest("m.yaml", "flights:\n  - bag: a.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n");
  EXPECT_EQ(run("--model x.yaml --manifest " + file("m.yaml")).status, 2);  // no --out
  EXPECT_EQ(diagnose("m.yaml", "--jobs 0").status, 2);

  const ToolRun topic = diagnose("m.yaml", "--topic truth=/sim/truth");
  EXPECT_EQ(topic.status, 1);
  EXPECT_EQ(topic.err,
            "diagnose_gap: --topic truth=/sim/truth: 'truth' is not a signal (one of rc_out, battery, imu, pose, "
            "velocity, static_pressure, air_temperature, rangefinder, motor_temperature, esc_telemetry, "
            "esc_status)\n");
  const ToolRun bare = diagnose("m.yaml", "--topic imu");
  EXPECT_EQ(bare.status, 1);
  EXPECT_EQ(bare.err, "diagnose_gap: --topic imu: expected NAME=TOPIC\n");

  const ToolRun diameter = diagnose("m.yaml", "--rotor-diameter-m 5");
  EXPECT_EQ(diameter.status, 1);
  EXPECT_EQ(diameter.err, "diagnose_gap: --rotor-diameter-m: 5 is outside 0..3 m (must be positive)\n");
  const ToolRun lag = diagnose("m.yaml", "--rotor-time-constant-s 2");
  EXPECT_EQ(lag.status, 1);
  EXPECT_EQ(lag.err, "diagnose_gap: --rotor-time-constant-s: 2 is outside 0..1 s\n");

  writeManifest("empty.yaml", "flights: []\n");
  const ToolRun empty = diagnose("empty.yaml");
  EXPECT_EQ(empty.status, 1);
  EXPECT_EQ(empty.err, "diagnose_gap: " + file("empty.yaml") + ":1: flights: no flights\n");

  const ToolRun model = run("--model " + file("absent.yaml") + " --manifest " + file("m.yaml") + " --out " +
                            file("report"));
  EXPECT_EQ(model.status, 1);
  EXPECT_EQ(model.err.rfind("diagnose_gap: " + file("absent.yaml") + ": ", 0), 0u) << model.err;
  EXPECT_EQ(std::count(model.err.begin(), model.err.end(), '\n'), 1) << model.err;
}

// A model without bench air can be diagnosed; air_density is then not testable, and says why.
TEST_F(DiagnoseGapTool, ModelWithoutBenchAirLeavesAirDensityUntestable) {
  std::string model = slurp(repoPath("config/e300_dji2212_dji9443.yaml"));
  for (const char* key : {"  bench_air_temperature_c: 22\n", "  bench_air_pressure_pa: 101325\n"}) {
    const std::size_t at = model.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    model.erase(at, std::string(key).size());
  }
  std::ofstream(file("no_air.yaml")) << model;
  writeFlightBag(file("a.bag"), 10.0);
  writeManifest("m.yaml", "flights:\n  - bag: a.bag\n    segments:\n      - {start: 2, end: 8, mass_kg: 1.315}\n");
  const ToolRun r = run("--model " + file("no_air.yaml") + " --manifest " + file("m.yaml") + " --out " +
                        file("report") + " --python /usr/bin/python3");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string report = slurp(dir_ / "report" / "report.yaml");
  EXPECT_NE(report.find("name: air_density\n    testable: false\n    reason: the model has no bench air "
                        "(metadata bench_air_temperature_c, bench_air_pressure_pa)"),
            std::string::npos)
      << report;
}

// The README's CrazyPAD diagnosis (real flights, motor 3's propeller cut since the healthy ones):
// the terminal's summary names the suspect motor, and says that the onboard check judged none of
// the three flights rather than that it flagged none (a 30 g vehicle is below the node's default
// hover mass).
TEST_F(DiagnoseGapTool, SaysOnTheTerminalWhichMotorAndWhatTheOnboardCheckJudged) {
  const std::string data = repoPath("test/data/crazypad/");
  const ToolRun r = run("--model " + data + "crazyflie21_model.yaml --urdf " + data + "crazyflie21.urdf --manifest " +
                        data + "cut_M3_3mm_E8.manifest.yaml --reference " + data + "healthy_E8.manifest.yaml --out " +
                        file("cf") + " --python /usr/bin/python3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\nsuspect motor: channel 3, modelled 6.6 +- 3.3 % above its share against the vehicle's healthy "
                       "flights; it gives 93.8 % of its modelled thrust\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\nonboard motor-health check: judged on 0 of 3 flights, a motor flagged on 0 (not judged: no "
                       "steady hover the node's check accepts at its default parameters); "),
            std::string::npos)
      << r.out;
  // The corrected model's header says the healthy level folded into thrust_loss is no selected
  // effect.
  EXPECT_EQ(slurp(fs::path(file("cf/corrected_model.yaml"))).rfind("# " + data + "crazyflie21_model.yaml with the effects "
                                                                   "diagnose_gap selected (none) and the vehicle's "
                                                                   "level on its healthy flights, 0.8171 of the "
                                                                   "model's thrust, in thrust_loss; see report.md\n",
                                                                   0),
            0u);
  // An effect a Crazyflie log cannot test names the signal as the log's reading notes do, not a
  // bag's topic.
  EXPECT_NE(slurp(fs::path(file("cf/report.yaml"))).find("reason: needs battery current on the log's battery\n"),
            std::string::npos);
  EXPECT_NE(r.out.find("  battery: pm.vbatMV (mV), no current (a Crazyflie has no current sensor)\n"), std::string::npos)
      << r.out;
  // The flights lie inside the model's box but not where the bench logged: the report says so, not
  // that the box misses them.
  std::ifstream report(file("cf/report.md"));
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("24 of 24 blocks lie outside the model's domain: the flights' battery reads 3.31-3.42 V and their "
                    "pulse widths 1626-1845 us, inside the model's box (3.30-4.01 V, 1000-1938 us), but at 1736 us the "
                    "bench logged only 3.57-3.57 V (outside: clamp)"),
            std::string::npos)
      << md;
  // The segments as the manifest gives them.
  std::ifstream yaml_file(file("cf/report.yaml"));
  const std::string yaml((std::istreambuf_iterator<char>(yaml_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(yaml.find("- {start: 5.2, end: 10.3, mass_kg: 0.03}"), std::string::npos) << yaml;
  // The corrected model's thrust_loss holds the vehicle's healthy level, no selected effect: its
  // header says so.
  std::ifstream corrected(file("cf/corrected_model.yaml"));
  std::string header;
  std::getline(corrected, header);
  EXPECT_EQ(header, "# " + data + "crazyflie21_model.yaml with the effects diagnose_gap selected (none) and the "
                    "vehicle's level on its healthy flights, 0.8171 of the model's thrust, in thrust_loss; see report.md");
}

// A mass written in grams under mass_kg (30 for a 30 g Crazyflie): no effect halves the thrust a
// thousandfold, and the tool says what to check, on the terminal and in the report.
TEST_F(DiagnoseGapTool, SaysAMassInGramsIsNoEffect) {
  const std::string logs = repoPath("test/data/crazypad/cut_propeller_M3_3mm/");
  writeManifest("grams.yaml", "flights:\n  - log: " + logs + "E8_log01\n    segments:\n"
                              "      - {start: 5.2, end: 10.3, mass_kg: 30}\n      - {start: 19, end: 24.4, mass_kg: 30}\n");
  const ToolRun r = run("--model " + repoPath("test/data/crazypad/crazyflie21_model.yaml") + " --manifest " +
                        file("grams.yaml") + " --out " + file("g") + " --python /usr/bin/python3");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string problem = "problem: " + logs + "E8_log01: the model gives 0.1 % of the thrust its weighed mass needs: "
                              "is mass_kg in kg (not grams), the vehicle airborne in every segment, and the model this "
                              "vehicle's?\n";
  EXPECT_NE(r.out.find(problem), std::string::npos) << r.out;
  std::ifstream report(file("g/report.md"));
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find(problem.substr(9, problem.size() - 10)), std::string::npos) << md;
}

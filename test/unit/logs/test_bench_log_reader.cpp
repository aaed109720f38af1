#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "propulsion_estimator/logs/bench_csv.h"
#include "propulsion_estimator/logs/bench_log_reader.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/units.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

std::string refusal(const std::string& text, const pe::BenchReadOptions& options = {}) {
  try {
    pe::parseBenchLog(text, "log.csv", options);
  } catch (const pe::DataError& e) {
    return e.what();
  }
  return "accepted";
}

const std::vector<double>& column(const pe::BenchLog& log, pe::BenchColumn c) { return log.column(c); }

const std::string kStrawson = "test/data/strawson_motor_propeller/";

// The first lines of an RCbenchmark 1520 export, byte for byte as the stand writes them.
const std::string kTytoHeader =
    "\xEF\xBB\xBFTime (s),ESC signal (\xC2\xB5s),Servo 1 (\xC2\xB5s),Thrust (gf),Voltage (V),Current (A),"
    "Motor Electrical Speed (RPM),Motor Optical Speed (RPM),Electrical Power (W),App message,\n";

}  // namespace

// --- native format ---------------------------------------------------------------------------

TEST(NativeBenchCsv, ReadsColumnsInAnyOrderWithMetadataAndExtras) {
  const pe::BenchLog log = pe::parseNativeBenchCsv(
      "# supply: regulated\n# air_temperature_c: 21.5\n# a plain comment\n"
      "voltage_v,note,thrust_g,pwm_us,current_a\n"
      "11.1,start,100,1500,3.5\n"
      "\n"
      "# mid-file comment\n"
      "11.0,\"a, b\",200,1600,5.25\n",
      "n.csv");
  ASSERT_EQ(log.rows(), 2u);
  EXPECT_EQ(log.line_numbers, (std::vector<int>{5, 8}));
  EXPECT_EQ(log.metadata.at("supply"), "regulated");
  EXPECT_EQ(log.metadata.at("air_temperature_c"), "21.5");
  EXPECT_EQ(log.metadata.size(), 2u);
  EXPECT_EQ(column(log, pe::BenchColumn::kPwm), (std::vector<double>{1500, 1600}));
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kThrust)[1], 200 * pe::kNewtonPerGramForce);
  EXPECT_EQ(column(log, pe::BenchColumn::kCurrent), (std::vector<double>{3.5, 5.25}));
  EXPECT_FALSE(log.has(pe::BenchColumn::kRpm));
  EXPECT_EQ(log.extra_columns.at("note"), (std::vector<std::string>{"start", "a, b"}));
}

TEST(NativeBenchCsv, WriterAndReaderRoundTrip) {
  pe::BenchLog log;
  log.metadata = {{"esc", "DJI E300"}, {"supply", "battery"}, {"thrust_noise_sigma_g", "2.5"}};
  log.column(pe::BenchColumn::kTime) = {0.0, 0.5, 1.0};
  log.column(pe::BenchColumn::kPwm) = {1200, 1500, 1900};
  log.column(pe::BenchColumn::kVoltage) = {12.5432, 12.4, 12.21};
  log.column(pe::BenchColumn::kThrust) = {0.1234, 2.5, 6.75};
  log.column(pe::BenchColumn::kRpm) = {2000, 5000, 8600};
  log.column(pe::BenchColumn::kMotorTemp) = {25, 30.5, 41};
  log.extra_columns["remark"] = {"", "x,y", "say \"hi\""};
  log.line_numbers = {1, 2, 3};
  for (pe::ThrustUnit unit : {pe::ThrustUnit::kGram, pe::ThrustUnit::kNewton}) {
    std::ostringstream out;
    pe::writeNativeBenchCsv(log, out, unit);
    const pe::BenchLog back = pe::parseNativeBenchCsv(out.str(), "rt.csv");
    EXPECT_EQ(back.metadata, log.metadata);
    EXPECT_EQ(back.extra_columns, log.extra_columns);
    for (int c = 0; c < pe::kBenchColumnCount; ++c) {
      ASSERT_EQ(back.columns[c].size(), log.columns[c].size()) << c;
      for (std::size_t r = 0; r < log.columns[c].size(); ++r) {
        EXPECT_NEAR(back.columns[c][r], log.columns[c][r], 1e-6 * std::abs(log.columns[c][r])) << c << "," << r;
      }
    }
    EXPECT_EQ(back.line_numbers, (std::vector<int>{5, 6, 7}));  // after three metadata lines and the header
  }
}

TEST(NativeBenchCsv, RefusesMissingColumn) {
  EXPECT_EQ(refusal("pwm_us,thrust_g\n1500,100\n"),
            "log.csv:1: missing column 'voltage_v' (required: pwm_us, voltage_v, and thrust_g or thrust_n)");
  EXPECT_EQ(
      refusal("# x: 1\npwm_us,voltage_v\n1500,11\n"),
      "log.csv:2: missing column 'thrust_g' or 'thrust_n' (required: pwm_us, voltage_v, and thrust_g or thrust_n)");
}

TEST(NativeBenchCsv, RefusesTextInANumberField) {
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g\n1500,11.1,100\n1600,11.1,abc\n"),
            "log.csv:3: column 3 'thrust_g': 'abc' is not a number");
}

TEST(NativeBenchCsv, ReadsCommentLinesOfAnyLength) {
  // 50,000 characters: a regular expression overflowed the stack on such a line.
  const std::string long_text(50000, 'x');
  const pe::BenchLog log = pe::parseNativeBenchCsv("#" + long_text + "\n#  note :  " + long_text + " \t\n# a: b: c\n" +
                                                       "#:x\n# bad key: y\n#empty:\npwm_us,voltage_v,thrust_g\n1500,11,100\n",
                                                   "n.csv");
  EXPECT_EQ(log.metadata.size(), 3u);
  EXPECT_EQ(log.metadata.at("note"), long_text);
  EXPECT_EQ(log.metadata.at("a"), "b: c");
  EXPECT_EQ(log.metadata.at("empty"), "");
}

TEST(NativeBenchCsv, RefusesNaN) {
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g\n1500,nan,100\n"),
            "log.csv:2: column 2 'voltage_v': 'nan' is not a finite number");
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g\n1500,11,-inf\n"),
            "log.csv:2: column 3 'thrust_g': '-inf' is not a finite number");
}

TEST(NativeBenchCsv, RefusesEmptyFile) {
  EXPECT_EQ(refusal(""), "log.csv: empty file (no header line)");
  EXPECT_EQ(refusal("\xEF\xBB\xBF\n# only comments\n\n"), "log.csv: empty file (no header line)");
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g\n"), "log.csv: no data rows after the header");
}

TEST(NativeBenchCsv, RefusesMalformedRowsAndHeaders) {
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g\n1500,11\n"), "log.csv:2: 2 fields, the header has 3 columns");
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g\n1500,,100\n1600,11,120\n"),
            "log.csv:2: column 2 'voltage_v': empty cell (the column has values in other rows)");
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g,pwm_us\n1,2,3,4\n"),
            "log.csv:1: column 'pwm_us' appears twice (columns 1 and 4)");
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g,thrust_n\n1,2,3,4\n"),
            "log.csv:1: both thrust_g and thrust_n are given; keep one");
  EXPECT_EQ(refusal("# esc: a\n# esc: b\npwm_us,voltage_v,thrust_g\n1,2,3\n"),
            "log.csv:2: metadata key 'esc' given twice (first on line 1)");
  EXPECT_EQ(refusal("pwm_us,voltage_v,thrust_g\n1500,11,\"10\"0\n"),
            "log.csv:2: error parsing data while strict checking enabled (a quote inside an unquoted field, or text "
            "after a closing quote)");
  EXPECT_EQ(refusal("time,speed\n1,2\n"),
            "log.csv:1: not a bench log: the header has neither the native columns (pwm_us, voltage_v, thrust_g or "
            "thrust_n) nor an RCbenchmark/Tyto 'ESC signal (\xC2\xB5s)' column");
}

TEST(NativeBenchCsv, ReadsSemicolonsWithDecimalCommas) {
  const pe::BenchLog log =
      pe::parseBenchLog("pwm_us;voltage_v;thrust_g\n1500;11,1;100,5\n1600;11,0;120\n", "s.csv", {});
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kVoltage)[0], 11.1);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kThrust)[0], 100.5 * pe::kNewtonPerGramForce);
  EXPECT_EQ(log.notes, (std::vector<std::string>{"numbers read with a decimal comma (';'-separated file)"}));
  EXPECT_EQ(refusal("pwm_us;voltage_v;thrust_g\n1500;11,1;100.5\n"),
            "log.csv:2: column 3 'thrust_g': '100.5' is not a number (this file uses decimal commas)");
  pe::BenchReadOptions points;
  points.decimal = pe::DecimalSeparator::kPoint;
  EXPECT_EQ(refusal("pwm_us;voltage_v;thrust_g\n1500;11,1;100\n", points),
            "log.csv:2: column 2 'voltage_v': '11,1' is not a number (decimal points were asked for)");
}

// --- Tyto / RCbenchmark format -------------------------------------------------------------------

TEST(TytoBenchCsv, ReadsTheRealStrawsonExport) {
  const pe::BenchLog log = pe::readBenchLog(repoPath(kStrawson + "a1_11.csv"));
  ASSERT_EQ(log.rows(), 11u);
  EXPECT_EQ(log.line_numbers.front(), 2);
  // Row 1 of the file: 0,1050,,,,15.171654199725802,11.091128183929616,0.5113728685208023,3421,0,5.538...
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kPwm)[0], 1050);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kThrust)[0], 15.171654199725802 * pe::kNewtonPerGramForce);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kVoltage)[0], 11.091128183929616);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kCurrent)[0], 0.5113728685208023);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kRpm)[0], 3421);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kPower)[0], 5.538871806110033);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kTime)[10], 17.857648886999996);
  // The optical tachometer was not connected: its zeros are not taken for rpm.
  EXPECT_EQ(log.notes, (std::vector<std::string>{
                           "UTF-8 byte-order mark skipped",
                           "rpm from 'Motor Electrical Speed (RPM)'; 'Motor Optical Speed (RPM)' is zero in every row",
                           "rpm is the motor's electrical speed: mechanical rpm only if the stand software knew the "
                           "motor's pole count"}));
  EXPECT_EQ(log.extra_columns.count("Servo 1 (\xC2\xB5s)"), 1u);
  EXPECT_EQ(log.extra_columns.count("Motor Optical Speed (RPM)"), 1u);
  EXPECT_EQ(log.extra_columns.count("Overall Efficiency (gf/W)"), 1u);
  EXPECT_EQ(log.extra_columns.count("App message"), 1u);
  EXPECT_EQ(log.extra_columns.size(), 6u);  // 13 columns, 7 used: 3 servos, optical rpm, efficiency, app message
}

TEST(TytoBenchCsv, NegatesAThrustLoggedNegativeAndSaysSo) {
  // m7_11: a pusher-mounted run, thrust from -214 gf up to +1 gf of idle noise.
  const pe::BenchLog log = pe::readBenchLog(repoPath(kStrawson + "m7_11.csv"));
  const auto& thrust = column(log, pe::BenchColumn::kThrust);
  EXPECT_GT(*std::max_element(thrust.begin(), thrust.end()), 200 * pe::kNewtonPerGramForce);
  ASSERT_EQ(log.notes.size(), 4u);
  EXPECT_EQ(log.notes[1].rfind("'Thrust (gf)' negated (from -214.", 0), 0u) << log.notes[1];
  EXPECT_NE(log.notes[1].find("as logged, logged negative as a pusher mounting or reversed sensor gives)"),
            std::string::npos)
      << log.notes[1];
}

TEST(TytoBenchCsv, HandlesSemicolonsDecimalCommasNegativeCurrentAndExtraColumns) {
  const std::string text =
      "Time (s);ESC signal (\xC2\xB5s);AccX (g);Torque (N\xC2\xB7m);Thrust (kgf);Voltage (V);Current (A);"
      "Electrical Power (W);Motor Optical Speed (RPM);Vibration (g);App message;\n"
      "0;1100;0,01;-0,002;-0,050;12,4;-1,5;-18,6;3000;0,1;;\n"
      "1;1500;0,02;-0,020;-0,400;12,2;-6,0;-73,2;7000;0,2;step 2;\n";
  const pe::BenchLog log = pe::parseBenchLog(text, "pusher.csv", {});
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kThrust)[1], 0.4 * pe::kStandardGravity);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kCurrent)[1], 6.0);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kPower)[0], 18.6);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kVoltage)[0], 12.4);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kRpm)[1], 7000);
  EXPECT_EQ(log.extra_columns.at("App message"), (std::vector<std::string>{"", "step 2"}));
  EXPECT_EQ(log.extra_columns.size(), 4u);
  EXPECT_EQ(log.notes, (std::vector<std::string>{
                           "numbers read with a decimal comma (';'-separated file)",
                           "'Thrust (kgf)' negated (from -0.4 to -0.05 as logged, logged negative as a pusher "
                           "mounting or reversed sensor gives)",
                           "'Current (A)' negated (from -6 to -1.5 as logged, logged negative as a pusher mounting or "
                           "reversed sensor gives)",
                           "'Electrical Power (W)' negated (from -73.2 to -18.6 as logged, logged negative as a pusher "
                           "mounting or reversed sensor gives)"}));
}

TEST(TytoBenchCsv, RefusesAmbiguousContentAndOffersTheOption) {
  const std::string mixed = kTytoHeader +
                            "0,1100,,-120,12,1,2000,0,12,,\n"
                            "1,1500,,340,12,5,6000,0,60,,\n";
  EXPECT_EQ(refusal(mixed),
            "log.csv: column 'Thrust (gf)' has both signs (from -120 to 340): say how the stand was mounted with "
            "--thrust-sign as-logged or --thrust-sign negate");
  pe::BenchReadOptions as_logged;
  as_logged.thrust_sign = pe::SignPolicy::kAsLogged;
  EXPECT_EQ(refusal(mixed, as_logged), "accepted");

  const std::string two_rpm = kTytoHeader +
                              "0,1100,,100,12,1,2000,1990,12,,\n"
                              "1,1500,,340,12,5,6000,5990,60,,\n";
  EXPECT_EQ(refusal(two_rpm),
            "log.csv:1: two rpm columns with values, 'Motor Electrical Speed (RPM)' and 'Motor Optical Speed (RPM)': "
            "choose one with --map rpm=<column>");
  pe::BenchReadOptions optical;
  optical.columns[pe::BenchColumn::kRpm] = "Motor Optical Speed (RPM)";
  const pe::BenchLog log = pe::parseBenchLog(two_rpm, "log.csv", optical);
  EXPECT_DOUBLE_EQ(column(log, pe::BenchColumn::kRpm)[1], 5990);

  pe::BenchReadOptions missing;
  missing.columns[pe::BenchColumn::kMotorTemp] =
      "Temp 1 (\xC2\xBA"
      "C)";
  EXPECT_EQ(refusal(two_rpm, missing),
            "log.csv:1: no column 'Temp 1 (\xC2\xBA"
            "C)' for motor_temp_c (--map motor_temp_c=...)");
}

TEST(TytoBenchCsv, RefusesMissingColumnAndTextCells) {
  EXPECT_EQ(refusal("Time (s),ESC signal (\xC2\xB5s),Thrust (kgf),Current (A)\n0,1100,0.1,1\n"),
            "log.csv:1: missing column 'Voltage (V)'");
  EXPECT_EQ(refusal(kTytoHeader + "0,1100,,100,12,1,2000,0,12,,\n1,1500,,oops,12,5,6000,0,60,,\n"),
            "log.csv:3: column 4 'Thrust (gf)': 'oops' is not a number");
}

// --- directories -------------------------------------------------------------------------------

TEST(BenchLogPaths, ExpandsADirectoryToItsCsvFilesSortedEachFileOnce) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "pe_bench_paths";
  fs::remove_all(dir);
  fs::create_directories(dir / "sub");
  for (const char* name : {"b.csv", "a.csv", "notes.txt", "sub/c.csv"}) std::ofstream(dir / name) << "x\n";
  fs::create_symlink(dir / "a.csv", dir / "sub" / "link.csv");
  // b.csv named alone, then again through its directory; a.csv through the directory and a link.
  const std::vector<pe::BenchLogFile> files = pe::expandBenchLogPaths(
      {(dir / "b.csv").string(), dir.string(), (dir / "sub" / "link.csv").string(), (dir / "sub" / "c.csv").string()});
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].path, (dir / "b.csv").string());
  EXPECT_EQ(files[0].also_named_by, std::vector<std::string>{dir.string()});
  EXPECT_EQ(files[1].path, (dir / "a.csv").string());
  EXPECT_EQ(files[1].also_named_by, std::vector<std::string>{(dir / "sub" / "link.csv").string()});
  EXPECT_EQ(files[2].path, (dir / "sub" / "c.csv").string());
  EXPECT_TRUE(files[2].also_named_by.empty());
  try {
    pe::expandBenchLogPaths({(dir / "sub" / "none").string()});
    FAIL();
  } catch (const pe::InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "sub" / "none").string() + ": no such file or directory");
  }
  fs::remove_all(dir / "sub");
  fs::remove(dir / "a.csv");
  fs::remove(dir / "b.csv");
  try {
    pe::expandBenchLogPaths({dir.string()});
    FAIL();
  } catch (const pe::InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir.string() + ": directory has no *.csv files");
  }
  fs::remove_all(dir);
}

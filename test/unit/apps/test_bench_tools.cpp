// The installed command lines, run as a user runs them (the built executables, which find the
// plot script next to themselves).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <new>
#include <regex>
#include <stdexcept>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/model/drive_curve.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/model/propulsion_model.h"
#include "test_paths.h"
#include "tool_command.h"
#include "tool_process.h"

namespace pe = propulsion_estimator;
namespace fs = std::filesystem;

namespace {

class BenchTools : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pe_tools_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  ToolRun run(const std::string& tool, const std::string& arguments) const { return runTool(tool, arguments, dir_); }

  static std::string strawson(const std::string& file) { return repoPath("test/data/strawson_motor_propeller/" + file); }

  static std::string metadata(const std::string& propeller) {
    return "--esc unknown --motor 'Lumenier RX2206-13 2000kv' --propeller " + quoted(propeller) +
           " --air-temperature-c 20 --air-pressure-pa 101325 --supply regulated";
  }

  fs::path dir_;
};

}  // namespace

TEST_F(BenchTools, FitSurfacesTurnsADirectoryOfLogsIntoAModelAndAReport) {
  const fs::path logs = dir_ / "logs";
  fs::create_directories(logs);
  fs::copy_file(strawson("g1_7.csv"), logs / "g1_7.csv");
  fs::copy_file(strawson("g1_11.csv"), logs / "g1_11.csv");
  const std::string model = (dir_ / "g1.yaml").string();
  const ToolRun r =
      run(PE_FIT_SURFACES, "--out " + model + " --report " + (dir_ / "report").string() +
                               " --python /usr/bin/python3 " + metadata("Cyclone T5040C") + " " + logs.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("thrust     surface  (3,1)          22"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model: " + model), std::string::npos) << r.out;
  // The estimator's loader takes the file as written.
  const pe::PropulsionModel loaded = pe::loadModelFile(model);
  EXPECT_EQ(loaded.metadata().propeller, "Cyclone T5040C");
  EXPECT_NEAR(loaded.evaluateRaw(pe::Output::kThrust, 2000, 10.9), 340.0, 8.0);
  const std::string report = slurp(dir_ / "report" / "fit_report.md");
  EXPECT_NE(report.find("Model written to `" + model + "`"), std::string::npos);
  EXPECT_NE(report.find("| thrust | g | surface | (3, 1) | 22 |"), std::string::npos) << report;
  for (const char* figure :
       {"fit_sections_pwm.png", "fit_sections_voltage.png", "fit_residuals.png", "fit_surfaces.png"}) {
    EXPECT_NE(report.find(std::string("](") + figure + ")"), std::string::npos) << figure;
    EXPECT_GT(fs::file_size(dir_ / "report" / figure), 20000u) << figure;
  }
}

TEST_F(BenchTools, FitSurfacesFindsTheEscsFullThrottleEndPointOnARealDischargeAndSaysSo) {
  // The EMAX RS1108 on 2S: the first sweep's thrust and current stay flat from about 1850 us on.
  std::string logs;
  for (const char* file : {"StepsTest_2020-06-16_212137.csv", "StepsTest_2020-06-16_212732.csv",
                           "StepsTest_2020-06-16_213055.csv"}) {
    logs += " " + repoPath(std::string("test/data/diegosdantonio_thruststand/") + file);
  }
  const std::string model = (dir_ / "emax2s.yaml").string();
  const ToolRun r = run(PE_FIT_SURFACES, "--out " + model + " --report " + (dir_ / "report").string() +
                                             " --python /usr/bin/python3 --supply battery --steady-voltage-mad 0.001 "
                                             "--voltage-bin 0.07 --air-temperature-c 20 --air-pressure-pa 101325" +
                                             logs);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("thrust     surface  drive 2+ft     62"), std::string::npos) << r.out;
  const pe::PropulsionModel loaded = pe::loadModelFile(model);
  const pe::DriveCurve& thrust = *loaded.output(pe::Output::kThrust).surface->driveCurve();
  EXPECT_NEAR(thrust.pwmFullUs(), 1840.0, 40.0);
  // Full throttle: the logged 77-78 g at 7.2 V whatever the command above the end point.
  EXPECT_NEAR(loaded.evaluateRaw(pe::Output::kThrust, 1980.0, 7.2), 77.5, 2.0);
  EXPECT_EQ(loaded.evaluateRaw(pe::Output::kThrust, 1980.0, 7.2), loaded.evaluateRaw(pe::Output::kThrust, 1900.0, 7.2));
  const std::string report = slurp(dir_ / "report" / "fit_report.md");
  EXPECT_TRUE(std::regex_search(report, std::regex(R"(\| thrust \| g \| surface \| drive curve, degree 2, full throttle at 18[0-9][0-9] us \|)")))
      << report;
  EXPECT_NE(report.find("| **drive curve 2 + full throttle** |"), std::string::npos) << report;
}

TEST_F(BenchTools, FitSurfacesRefusesOneVoltageLevelWithTheCoreMessage) {
  const ToolRun r = run(PE_FIT_SURFACES, "--out " + (dir_ / "l3.yaml").string() + " " + metadata("Gemfan 5x4.5") + " " +
                                             strawson("l3_7.csv") + " " + strawson("l3_11.csv"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "fit_surfaces: cannot fit a surface: one voltage level only (all 22 rows of " +
                       strawson("l3_7.csv") + " and " + strawson("l3_11.csv") +
                       " have voltage_v near 7.36 V, 7.13 to 7.44 V); log sweeps at two or more supply voltages, or a "
                       "battery discharge\n");
  EXPECT_FALSE(fs::exists(dir_ / "l3.yaml"));
}

TEST_F(BenchTools, FitSurfacesRefusesAGroupingThatLeavesOneVoltageLevelPerFold) {
  const ToolRun r = run(PE_FIT_SURFACES, "--group-by voltage --out " + (dir_ / "g1.yaml").string() + " " +
                                             metadata("T5040C") + " " + strawson("g1_7.csv") + " " +
                                             strawson("g1_11.csv"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "fit_surfaces: cannot fit thrust: --group-by voltage leaves one voltage level in a training fold (without "
            "the 7.40 V level only 11.07 V remains), so cross-validation cannot score a voltage term: use --group-by "
            "pwm or auto\n");
  EXPECT_FALSE(fs::exists(dir_ / "g1.yaml"));
}

TEST_F(BenchTools, FitSurfacesWritesNoModelTheLoaderWouldRefuse) {
  // The bench air temperature in kelvin: the loader's range check, applied before writing.
  const ToolRun r = run(PE_FIT_SURFACES, "--out " + (dir_ / "g1.yaml").string() +
                                             " --esc E --motor M --propeller P --air-temperature-c 293.15 "
                                             "--air-pressure-pa 101325 --supply regulated " +
                                             strawson("g1_7.csv") + " " + strawson("g1_11.csv"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "fit_surfaces: metadata.bench_air_temperature_c: 293.15 is not an air temperature in deg C (given as "
            "--air-temperature-c)\n");
  EXPECT_FALSE(fs::exists(dir_ / "g1.yaml"));
}

TEST_F(BenchTools, FitSurfacesReadsALogNamedTwiceOnce) {
  const fs::path logs = dir_ / "logs";
  fs::create_directories(logs);
  fs::copy_file(strawson("g1_7.csv"), logs / "g1_7.csv");
  fs::copy_file(strawson("g1_11.csv"), logs / "g1_11.csv");
  const ToolRun r = run(PE_FIT_SURFACES, "--out " + (dir_ / "g1.yaml").string() + " " + metadata("T5040C") + " " +
                                             (logs / "g1_7.csv").string() + " " + logs.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("note: " + (logs / "g1_7.csv").string() + ": named again by the argument " + logs.string() +
                       ": read once\n"),
            std::string::npos)
      << r.out;
  // 11 rows per sweep, each counted once.
  EXPECT_NE(r.out.find("thrust     surface  (3,1)          22"), std::string::npos) << r.out;
}

TEST_F(BenchTools, FitSurfacesRefusesAThrustThatFallsAsPwmRises) {
  // A stand whose thrust reads negative, its sign kept as logged on purpose: no surface that rises
  // with PWM fits it, and none is written.
  std::ofstream(dir_ / "a.csv") << "# esc: E\n# motor: M\n# propeller: P\n# supply: battery\n"
                                   "# air_temperature_c: 20\n# air_pressure_pa: 100000\n"
                                   "pwm_us,voltage_v,thrust_g\n"
                                   "1100,11.1,0\n1300,11.1,-20\n1500,11.1,-40\n1700,11.1,-60\n1900,11.1,-80\n"
                                   "1100,12,0\n1300,12,-20\n1500,12,-40\n1700,12,-60\n1900,12,-80\n";
  const ToolRun r =
      run(PE_FIT_SURFACES, "--out " + (dir_ / "bad.yaml").string() + " --report " + (dir_ / "report").string() +
                               " --python /usr/bin/python3 " + (dir_ / "a.csv").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "fit_surfaces: cannot fit thrust: no candidate surface rises with PWM and voltage over the bench's domain "
            "(does column thrust_n fall as PWM rises? a sensor read with the wrong sign)\n");
  EXPECT_FALSE(fs::exists(dir_ / "bad.yaml"));
}

TEST_F(BenchTools, FitSurfacesNamesEveryMissingBenchConditionAtOnceAndLeavesNamesUnknown) {
  // Real RCbenchmark exports: no '# key: value' lines at all.
  const std::string logs = " " + strawson("g1_7.csv") + " " + strawson("g1_11.csv");
  const std::string out = "--out " + (dir_ / "g1.yaml").string();
  const ToolRun bare = run(PE_FIT_SURFACES, out + logs);
  EXPECT_EQ(bare.status, 1);
  EXPECT_EQ(bare.err,
            "fit_surfaces: no log gives the bench's air_temperature_c (a '# air_temperature_c:' line or an "
            "ambient_temp_c column), air_pressure_pa (a '# air_pressure_pa:' line or a pressure_pa column) and supply "
            "(a '# supply:' line): pass --air-temperature-c, --air-pressure-pa and --supply\n");
  EXPECT_FALSE(fs::exists(dir_ / "g1.yaml"));
  const ToolRun pressure = run(PE_FIT_SURFACES, out + " --supply regulated --air-temperature-c 20" + logs);
  EXPECT_EQ(pressure.status, 1);
  EXPECT_EQ(pressure.err,
            "fit_surfaces: no log gives the bench's air_pressure_pa (a '# air_pressure_pa:' line or a pressure_pa "
            "column): pass --air-pressure-pa\n");
  // The names only describe the combination: what neither the logs nor the options give is "unknown".
  const ToolRun named = run(PE_FIT_SURFACES, out +
                                                 " --supply regulated --air-temperature-c 20 --air-pressure-pa 101325 "
                                                 "--motor 'Lumenier RX2206-13 2000kv'" +
                                                 logs);
  ASSERT_EQ(named.status, 0) << named.err;
  for (const char* key : {"esc", "propeller"}) {
    EXPECT_NE(named.out.find("note: " + std::string(key) + ": no log has a '# " + key +
                             ":' line; the model records 'unknown' (pass --" + key + " to name it)\n"),
              std::string::npos)
        << named.out;
  }
  EXPECT_EQ(named.out.find("note: motor:"), std::string::npos) << named.out;
  const pe::PropulsionModel model = pe::loadModelFile((dir_ / "g1.yaml").string());
  EXPECT_EQ(model.metadata().esc, "unknown");
  EXPECT_EQ(model.metadata().motor, "Lumenier RX2206-13 2000kv");
  EXPECT_EQ(model.metadata().propeller, "unknown");
}

TEST_F(BenchTools, FitSurfacesRefusesAnRpmThatFallsAsPwmRisesAndSaysHowToWriteTheRest) {
  // An ESC whose telemetry sends the electrical rpm as a signed 16-bit number: above 32767 the
  // column reads negative, and the rpm surface with it at the top of the PWM range.
  for (double volts : {11.1, 12.0}) {
    std::ofstream log(dir_ / ("sweep_" + std::to_string(static_cast<int>(volts)) + ".csv"));
    log << "# esc: E\n# motor: M\n# propeller: P\n# supply: regulated\n# air_temperature_c: 20\n"
           "# air_pressure_pa: 100000\npwm_us,voltage_v,thrust_g,rpm\n";
    for (int x = 1100; x <= 1900; x += 100) {
      const int electrical_rpm = static_cast<int>(60.0 * (x - 1000) * volts / 11.1);
      log << x << "," << volts << "," << 0.001 * (x - 1000) * (x - 1000) * volts / 11.1 << ","
          << (electrical_rpm > 32767 ? electrical_rpm - 65536 : electrical_rpm) << "\n";
    }
  }
  const std::string logs = " " + (dir_ / "sweep_11.csv").string() + " " + (dir_ / "sweep_12.csv").string();
  const ToolRun r = run(PE_FIT_SURFACES, "--out " + (dir_ / "m.yaml").string() + logs);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "fit_surfaces: cannot fit rpm: no candidate surface rises with PWM and voltage over the bench's domain "
            "(does column rpm fall as PWM rises? a sensor read with the wrong sign); leave it out with --without "
            "rpm\n");
  EXPECT_FALSE(fs::exists(dir_ / "m.yaml"));
  // As the message says (and before the logs: --without takes one output at a time).
  const ToolRun without = run(PE_FIT_SURFACES, "--out " + (dir_ / "m.yaml").string() + " --without rpm" + logs);
  ASSERT_EQ(without.status, 0) << without.err;
  EXPECT_EQ(pe::loadModelFile((dir_ / "m.yaml").string()).output(pe::Output::kRpm).source, pe::OutputSource::kNone);
}

TEST_F(BenchTools, FitSurfacesSaysWhenThePlotsCannotBeDrawn) {
  const std::string logs = " " + strawson("g1_7.csv") + " " + strawson("g1_11.csv");
  const std::string out = "--out " + (dir_ / "g1.yaml").string() + " --report " + (dir_ / "r").string() + " ";
  const ToolRun r = run(PE_FIT_SURFACES, out + metadata("T5040C") + " --python /bin/false" + logs);
  EXPECT_EQ(r.status, 1);
  // Debian's python3 has matplotlib (scripts/install_deps.sh): the message points at it.
  EXPECT_EQ(r.err,
            "fit_surfaces: /bin/false cannot import matplotlib and numpy, which the report's figures need: pass "
            "--python /usr/bin/python3, which has them\n");
  // Refused before the fit: nothing written.
  EXPECT_FALSE(fs::exists(dir_ / "r"));
  EXPECT_FALSE(fs::exists(dir_ / "g1.yaml"));

  // The default python3, when the first one on PATH lacks matplotlib (a pyenv or venv python).
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "python3") << "#!/bin/sh\nexit 1\n";
  fs::permissions(bin / "python3", fs::perms::owner_all);
  const ToolRun pyenv = run("/usr/bin/env", "PATH=" + quoted(bin.string() + ":" + std::getenv("PATH")) + " " +
                                                quoted(PE_FIT_SURFACES) + " " + out + metadata("T5040C") + logs);
  EXPECT_EQ(pyenv.status, 1);
  EXPECT_EQ(pyenv.err, "fit_surfaces: python3 (" + (bin / "python3").string() +
                           ") cannot import matplotlib and numpy, which the report's figures need: pass --python "
                           "/usr/bin/python3, which has them\n");

  const ToolRun missing = run(PE_FIT_SURFACES, out + metadata("T5040C") + " --plot-script /nonexistent.py" + logs);
  EXPECT_EQ(missing.status, 1);
  EXPECT_EQ(missing.err, "fit_surfaces: /nonexistent.py: plot script not found (--plot-script)\n");
}

TEST_F(BenchTools, FitSurfacesUsageAndReaderErrors) {
  EXPECT_EQ(run(PE_FIT_SURFACES, strawson("g1_7.csv")).status, 2);  // no --out
  std::ofstream(dir_ / "text.csv") << "pwm_us,voltage_v,thrust_g\n1500,11.1,100\n1600,11.1,abc\n";
  const ToolRun r = run(PE_FIT_SURFACES, "--out x.yaml " + (dir_ / "text.csv").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "fit_surfaces: " + (dir_ / "text.csv").string() + ":3: column 3 'thrust_g': 'abc' is not a number\n");
  const ToolRun map = run(PE_FIT_SURFACES, "--out x.yaml --map speed=RPM " + (dir_ / "text.csv").string());
  EXPECT_EQ(map.status, 2);
  EXPECT_EQ(map.err,
            "fit_surfaces: --map: 'speed' is not a bench quantity (one of time_s, pwm_us, voltage_v, thrust_n, current_a, "
            "power_w, rpm, ambient_temp_c, motor_temp_c, pressure_pa) (see --help)\n");
  const ToolRun no_column = run(PE_FIT_SURFACES, "--out x.yaml --map rpm " + (dir_ / "text.csv").string());
  EXPECT_EQ(no_column.status, 2);
  EXPECT_EQ(no_column.err, "fit_surfaces: --map: rpm is not QUANTITY=COLUMN (see --help)\n");
  const ToolRun bin = run(PE_FIT_SURFACES, "--out x.yaml --voltage-bin -1 " + (dir_ / "text.csv").string());
  EXPECT_EQ(bin.status, 2);
  EXPECT_EQ(bin.err, "fit_surfaces: --voltage-bin: -1 is not above 0 (see --help)\n");
}

// Where fit_surfaces writes is checked before the fit: a folder as the model, a path through a
// file, a file as the report's folder, a folder as the plot script. A missing folder is created.
TEST_F(BenchTools, FitSurfacesChecksWhereItWritesBeforeTheFit) {
  const std::string file = (dir_ / "file.txt").string();
  std::ofstream(file) << "x\n";
  const std::string logs = strawson("a1_7.csv") + " " + strawson("a1_11.csv") + " " + metadata("a1");
  // Refused before the fit: nothing new written (no model, no report folder; the run's own
  // captured output files aside, which the first run makes).
  const auto entries = [&] { return std::distance(fs::directory_iterator(dir_), fs::directory_iterator()); };
  run(PE_FIT_SURFACES, "--help");
  const auto refusal = [&](const std::string& options) {
    const auto before = entries();
    const ToolRun r = run(PE_FIT_SURFACES, options + " " + logs);
    EXPECT_EQ(entries(), before) << options;
    return std::to_string(r.status) + " " + r.err;
  };
  EXPECT_EQ(refusal("--out " + dir_.string() + "/"),
            "2 fit_surfaces: --out: " + dir_.string() + "/: a folder, not a file (see --help)\n");
  EXPECT_EQ(refusal("--out " + file + "/m.yaml"),
            "2 fit_surfaces: --out: " + file + "/m.yaml: " + file + " is a file, not a folder (see --help)\n");
  EXPECT_EQ(refusal("--out " + (dir_ / "m.yaml").string() + " --report " + file),
            "2 fit_surfaces: --report: " + file + ": a file, not a folder (see --help)\n");
  EXPECT_EQ(refusal("--out " + (dir_ / "m.yaml").string() + " --report " + (dir_ / "r").string() + " --plot-script " +
                    dir_.string()),
            "1 fit_surfaces: " + dir_.string() + ": a folder, not the plot script (--plot-script)\n");
  const ToolRun made = run(PE_FIT_SURFACES, "--out " + (dir_ / "new" / "m.yaml").string() + " " + logs);
  EXPECT_EQ(made.status, 0) << made.err;
  EXPECT_TRUE(fs::exists(dir_ / "new" / "m.yaml"));
}

TEST_F(BenchTools, FitSurfacesReadsAFiftyThousandCharacterCommentLine) {
  std::ofstream(dir_ / "long.csv") << "# " << std::string(50000, 'x') << "\n# note: " << std::string(50000, 'y')
                                   << "\npwm_us,voltage_v,thrust_g\n1500,11.1,100\n1600,11.1,abc\n";
  const ToolRun r = run(PE_FIT_SURFACES, "--out x.yaml " + (dir_ / "long.csv").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "fit_surfaces: " + (dir_ / "long.csv").string() + ":5: column 3 'thrust_g': 'abc' is not a number\n");
}

namespace {

// Runs runToolCommand("tool", ...) with `run` as the tool's work; its status and stderr.
ToolRun runInProcess(const std::function<int()>& work) {
  CLI::App app("a tool");
  std::string argument0 = "tool";
  char* argv[] = {argument0.data()};
  testing::internal::CaptureStderr();
  const int status = pe::runToolCommand("tool", app, 1, argv, work);
  return {status, "", testing::internal::GetCapturedStderr()};
}

}  // namespace

TEST(ToolCommand, AnyOtherExceptionIsOneInternalErrorLineAndStatusOne) {
  const ToolRun bad_alloc = runInProcess([]() -> int { throw std::bad_alloc(); });
  EXPECT_EQ(bad_alloc.status, 1);
  EXPECT_EQ(bad_alloc.err, "tool: internal error: std::bad_alloc\n");
  const ToolRun regex = runInProcess([]() -> int { throw std::regex_error(std::regex_constants::error_stack); });
  EXPECT_EQ(regex.status, 1);
  EXPECT_EQ(regex.err, "tool: internal error: " + std::string(std::regex_error(std::regex_constants::error_stack).what()) + "\n");
  const ToolRun runtime = runInProcess([]() -> int { throw std::runtime_error("unexpected"); });
  EXPECT_EQ(runtime.err, "tool: internal error: unexpected\n");
  // Refused inputs keep their own line; the tool's status passes through.
  const ToolRun refused = runInProcess([]() -> int { throw pe::DataError("f.csv: bad"); });
  EXPECT_EQ(refused.status, 1);
  EXPECT_EQ(refused.err, "tool: f.csv: bad\n");
  EXPECT_EQ(runInProcess([] { return 0; }).status, 0);
}

TEST_F(BenchTools, SimulateAnswersLikeTheOtherTools) {
  const std::string params = repoPath("config/sim/e300_dji2212_dji9443.yaml");
  const std::string csv = (dir_ / "sweep.csv").string();
  const ToolRun bad_option =
      run(PE_SIMULATE, "bench --params " + params + " --experiment pwm_sweep --output " + csv + " --bogus");
  EXPECT_EQ(bad_option.status, 2);
  EXPECT_EQ(bad_option.err, "simulate bench: The following argument was not expected: --bogus (see --help)\n");
  const ToolRun bad_value =
      run(PE_SIMULATE, "flight --params " + params + " --profile p.yaml --bag f.bag --compression zip");
  EXPECT_EQ(bad_value.status, 2);
  EXPECT_EQ(bad_value.err, "simulate flight: --compression: zip not in {none,bz2,lz4} (see --help)\n");
  // The ULog layout: one of the two, and only for a ULog.
  const ToolRun bad_layout =
      run(PE_SIMULATE, "flight --params " + params + " --profile p.yaml --log f.ulg --log-format ulog --ulog-layout px4-2");
  EXPECT_EQ(bad_layout.status, 2);
  EXPECT_EQ(bad_layout.err, "simulate flight: --ulog-layout: px4-2 not in {px4-1.12,px4-1.14} (see --help)\n");
  const ToolRun layout_of_a_bag =
      run(PE_SIMULATE, "flight --params " + params + " --profile p.yaml --log f.bag --ulog-layout px4-1.14");
  EXPECT_EQ(layout_of_a_bag.status, 1);
  EXPECT_EQ(layout_of_a_bag.err, "simulate flight: --ulog-layout: px4-1.14 is for --log-format ulog, not bag\n");
  // A positive number: a word, NaN, zero and below each refused by its value.
  for (const auto& [value, reason] : std::vector<std::pair<std::string, std::string>>{
           {"abc", "abc is not a number"}, {"nan", "nan is not a number"}, {"0", "0 is not above 0"},
           {"-1", "-1 is not above 0"}}) {
    const ToolRun step =
        run(PE_SIMULATE, "bench --params " + params + " --experiment pwm_sweep --output " + csv + " --pwm-step " + value);
    EXPECT_EQ(step.status, 2);
    EXPECT_EQ(step.err, "simulate bench: --pwm-step: " + reason + " (see --help)\n");
  }
  const ToolRun no_command = run(PE_SIMULATE, "");
  EXPECT_EQ(no_command.status, 2);
  EXPECT_EQ(no_command.err, "simulate: A subcommand is required (see --help)\n");
  const ToolRun refused =
      run(PE_SIMULATE, "bench --params " + (dir_ / "none.yaml").string() + " --experiment pwm_sweep --output " + csv);
  EXPECT_EQ(refused.status, 1);
  EXPECT_EQ(refused.err, "simulate bench: " + (dir_ / "none.yaml").string() + ": cannot open file\n");
  EXPECT_FALSE(fs::exists(csv));
  const ToolRun help = run(PE_SIMULATE, "bench --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("--experiment"), std::string::npos) << help.out;
  // The same line for the other tools.
  const ToolRun fit = run(PE_FIT_SURFACES, "--out x.yaml --bogus a.csv");
  EXPECT_EQ(fit.status, 2);
  EXPECT_EQ(fit.err, "fit_surfaces: The following argument was not expected: --bogus (see --help)\n");
  const ToolRun compare = run(PE_COMPARE_MODELS, "--bogus a.yaml b.yaml");
  EXPECT_EQ(compare.status, 2);
  EXPECT_EQ(compare.err, "compare_models: The following argument was not expected: --bogus (see --help)\n");
}

TEST_F(BenchTools, CompareModelsPrintsTheChapter7TableAndWritesTheReport) {
  for (const char* name : {"g4", "g5"}) {
    const ToolRun fit = run(PE_FIT_SURFACES, "--out " + (dir_ / (std::string(name) + ".yaml")).string() + " " +
                                                 metadata(name) + " " + strawson(std::string(name) + "_7.csv") + " " +
                                                 strawson(std::string(name) + "_11.csv"));
    ASSERT_EQ(fit.status, 0) << fit.err;
  }
  const ToolRun r = run(PE_COMPARE_MODELS,
                        "--voltage 11 --mass-kg 0.6 --cells 2 --capacity-mah 1300 --python /usr/bin/python3 --report " +
                            (dir_ / "cmp").string() + " " + (dir_ / "g4.yaml").string() + "=" + strawson("g4_7.csv") +
                            "," + strawson("g4_11.csv") + " " + (dir_ / "g5.yaml").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("| g4 | unknown | Lumenier RX2206-13 2000kv | g4 | 11.00 |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Hover of a 0.6 kg vehicle on 4 motors (150.0 g each), 2S 1300 mAh"), std::string::npos);
  const std::string report = slurp(dir_ / "cmp" / "compare_report.md");
  EXPECT_NE(report.find("# Comparison of 2 ESC-motor-propeller combinations"), std::string::npos);
  for (const char* figure : {"compare_curves.png", "compare_endurance.png"}) {
    EXPECT_NE(report.find(std::string("](") + figure + ")"), std::string::npos) << figure;
    EXPECT_GT(fs::file_size(dir_ / "cmp" / figure), 20000u) << figure;
  }
  const ToolRun one = run(PE_COMPARE_MODELS, (dir_ / "g4.yaml").string());
  EXPECT_EQ(one.status, 2);
  EXPECT_EQ(one.err, "compare_models: give two or more models to compare (see --help)\n");
  const std::string two = " " + (dir_ / "g4.yaml").string() + " " + (dir_ / "g5.yaml").string();
  const ToolRun partial = run(PE_COMPARE_MODELS, "--mass-kg 1" + two);
  EXPECT_EQ(partial.status, 2);
  EXPECT_EQ(partial.err, "compare_models: hover needs --mass-kg, --cells and --capacity-mah together (see --help)\n");
  const ToolRun cells = run(PE_COMPARE_MODELS, "--cells 3.5" + two);
  EXPECT_EQ(cells.status, 2);
  EXPECT_EQ(cells.err, "compare_models: --cells: 3.5 is not a whole number (see --help)\n");
}

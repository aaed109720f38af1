// estimate as a user runs it: on the public PX4 and ArduPilot logs in test/data, with a log that
// does not exist among them, and with options it refuses.
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "test_paths.h"
#include "tool_process.h"

namespace {

std::filesystem::path freshDirectory(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pe_estimate_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

const std::string kModel = "--model " + quoted(repoPath("config/e300_dji2212_dji9443.yaml"));

}  // namespace

TEST(EstimateTool, EstimatesEveryLogItCanReadAndNamesTheOneItCannot) {
  const std::filesystem::path dir = freshDirectory("logs");
  const std::string ulog = repoPath("test/data/px4_pyulog_sample_log_small/sample_log_small_cut.ulg");
  const std::string dataflash = repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin");
  const std::string missing = (dir / "missing.ulg").string();
  const ToolRun run = runTool(PE_ESTIMATE,
                              kModel + " --no-figures --jobs 2 --out " + quoted((dir / "out").string()) + " " +
                                  quoted(ulog) + " " + quoted(missing) + " " + quoted(dataflash),
                              dir);
  EXPECT_EQ(run.status, 1) << run.err;
  EXPECT_EQ(run.err, "estimate: " + missing + ": no such file\n");
  EXPECT_NE(run.out.find("estimated 2 of 3 logs"), std::string::npos) << run.out;
  // The ArduCopter flies three hovers; a 4-cell vehicle against the thesis' 3-cell model, and said so.
  const std::string copter = slurp(dir / "out/log171_cut/summary.md");
  EXPECT_NE(copter.find("| 3 | "), std::string::npos) << copter;
  EXPECT_NE(copter.find("the log's battery reads 14.91-16.54 V, its motors 1000-1853 us while armed); outside: "
                        "clamp: is this the right model for this vehicle?"),
            std::string::npos)
      << copter;
  const std::string sample = slurp(dir / "out/sample_log_small_cut/summary.md");
  EXPECT_NE(sample.find("No hover was found"), std::string::npos) << sample;
  EXPECT_NE(sample.find("the log's battery reads 23.34-23.46 V"), std::string::npos) << sample;
  EXPECT_FALSE(slurp(dir / "out/log171_cut/estimates.csv").empty());
  const std::string index = slurp(dir / "out/summary.md");
  EXPECT_NE(index.find("| " + missing + " | refused: " + missing + ": no such file | |"), std::string::npos) << index;
  EXPECT_NE(index.find("(log171_cut/summary.md) | 3 hovers ("), std::string::npos) << index;
}

// The ArduCopter's motors judged with its frame: a channel flagged in a few windows, gone by the
// last one, is said so, beside the summary's last window (no contradiction left to the user).
TEST(EstimateTool, SaysWhenAndHowOftenAMotorWasFlaggedBesideTheLastWindow) {
  const std::filesystem::path dir = freshDirectory("flagged");
  const ToolRun run =
      runTool(PE_ESTIMATE,
              kModel + " --no-figures --frame quad_x --arm-m 0.225 --out " + quoted((dir / "out").string()) + " " +
                  quoted(repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin")),
              dir);
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string summary = slurp(dir / "out/log171_cut/summary.md");
  EXPECT_NE(summary.find("Last window of 10 steady-hover blocks: no motor stands out."), std::string::npos) << summary;
  EXPECT_NE(summary.find("- the motor-health check flagged channel 4 in 3 of 52 judged windows, first 198 s into the "
                         "log (its share of the thrust beyond the healthy spread; diagnose_gap locates it); the last "
                         "window: no motor stands out\n"),
            std::string::npos)
      << summary;
}

TEST(EstimateTool, RefusesASampleRateOutsideItsRangeNamingTheOption) {
  const std::filesystem::path dir = freshDirectory("rate");
  const ToolRun run = runTool(PE_ESTIMATE,
                              kModel + " --no-figures --sample-rate-hz -1 --out " + quoted((dir / "out").string()) +
                                  " " + quoted(repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin")),
                              dir);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.err, "estimate: --sample-rate-hz: -1 is outside 0..1000 Hz\n");
}

// A word or a fraction given for a count is named as such, not as out of range (CLI11's Range).
TEST(EstimateTool, RefusesAJobCountThatIsNotAWholeNumberInRange) {
  const std::filesystem::path dir = freshDirectory("jobs");
  const auto refusal = [&](const std::string& jobs) {
    const ToolRun run = runTool(PE_ESTIMATE, kModel + " --jobs " + jobs + " --out " + quoted((dir / "out").string()) + " a.ulg", dir);
    EXPECT_EQ(run.status, 2) << jobs;
    return run.err;
  };
  EXPECT_EQ(refusal("abc"), "estimate: --jobs: abc is not a whole number (see --help)\n");
  EXPECT_EQ(refusal("2.5"), "estimate: --jobs: 2.5 is not a whole number (see --help)\n");
  EXPECT_EQ(refusal("70"), "estimate: --jobs: 70 is outside 1..64 (see --help)\n");
}

// A file given as the results' folder is refused before any log is read.
TEST(EstimateTool, RefusesAFileAsItsOutputFolder) {
  const std::filesystem::path dir = freshDirectory("out_file");
  std::ofstream(dir / "out") << "x\n";
  const ToolRun run = runTool(PE_ESTIMATE, kModel + " --out " + quoted((dir / "out").string()) + " a.ulg", dir);
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err, "estimate: --out: " + (dir / "out").string() + ": a file, not a folder (see --help)\n");
}

TEST(EstimateTool, RefusesAFrameWithoutItsArmLength) {
  const std::filesystem::path dir = freshDirectory("frame");
  const ToolRun run = runTool(PE_ESTIMATE,
                              kModel + " --no-figures --frame hexa_x --out " + quoted((dir / "out").string()) + " " +
                                  quoted(repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin")),
                              dir);
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err, "estimate: --frame hexa_x: needs --arm-m, the arm length in m (see --help)\n");
  // An unknown frame and a frame beside a URDF are usage errors too.
  const ToolRun unknown = runTool(PE_ESTIMATE, kModel + " --frame quad_y --arm-m 0.2 --out " + quoted((dir / "out").string()) + " a.bin", dir);
  EXPECT_EQ(unknown.status, 2);
  EXPECT_EQ(unknown.err, "estimate: --frame: quad_y not in {quad_x,hexa_x,octo_x} (see --help)\n");
  const ToolRun both = runTool(PE_ESTIMATE,
                               kModel + " --frame quad_x --arm-m 0.2 --urdf " + quoted(repoPath("config/f450_quad.urdf")) +
                                   " --out " + quoted((dir / "out").string()) + " a.bin",
                               dir);
  EXPECT_EQ(both.status, 2);
  EXPECT_EQ(both.err, "estimate: --frame: give the frame or --urdf, not both (see --help)\n");
}

TEST(EstimateTool, TakesTheNodesParametersFromAFileAsALaunchFileLoadsThem) {
  // A Crazyflie (about 30 g) never holds the node's default hover/min_mass_kg of 0.3 kg; with the
  // parameter set for it, each of its two airborne stretches is a hover.
  const std::filesystem::path dir = freshDirectory("params");
  const std::string log = repoPath("test/data/crazypad/normal_flight/E8_log00");
  const std::string vehicle = " --model " + quoted(repoPath("test/data/crazypad/crazyflie21_model.yaml")) +
                              " --urdf " + quoted(repoPath("test/data/crazypad/crazyflie21.urdf")) + " --no-figures";
  const ToolRun defaults = runTool(PE_ESTIMATE, vehicle + " --out " + quoted((dir / "a").string()) + " " + quoted(log), dir);
  EXPECT_EQ(defaults.status, 0) << defaults.err;
  EXPECT_NE(defaults.out.find("0 hovers"), std::string::npos) << defaults.out;
  EXPECT_NE(defaults.out.find("most often thrust below hover/min_mass_kg"), std::string::npos) << defaults.out;
  // estimate on the log with a parameter file `name` holding `text`, into its own folder.
  const auto withParams = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return runTool(PE_ESTIMATE,
                   vehicle + " --params " + quoted((dir / name).string()) + " --out " +
                       quoted((dir / (name + ".out")).string()) + " " + quoted(log),
                   dir);
  };
  const ToolRun tuned = withParams("params.yaml", "hover:\n  min_mass_kg: 0.01\n");
  EXPECT_EQ(tuned.status, 0) << tuned.err;
  EXPECT_NE(tuned.out.find("2 hovers"), std::string::npos) << tuned.out;
  EXPECT_NE(tuned.out.find("min_mass_kg 0.01"), std::string::npos) << tuned.out;  // each loaded value, once
  // The URDF the tool uses, not "(none)".
  EXPECT_NE(tuned.out.find("\n  urdf_file: " + repoPath("test/data/crazypad/crazyflie21.urdf") + "\n"), std::string::npos)
      << tuned.out;
  const ToolRun channels = withParams("channels.yaml", "motor_channels: [5, 6, 7, 8]\n");
  EXPECT_EQ(channels.status, 1);
  EXPECT_EQ(channels.err, "estimate: " + (dir / "channels.yaml").string() +
                              ": motor_channels: estimate reads motor k from the log's output k (1..4); leave it out\n");
  // A value the estimator refuses is named by the file and its key, not as an option.
  const ToolRun window = withParams("window.yaml", "hover:\n  window_s: -1\n");
  EXPECT_EQ(window.status, 1);
  EXPECT_EQ(window.err, "estimate: " + (dir / "window.yaml").string() +
                            ": hover/window_s: must be a positive number, got -1\n");
}

// --check reads the model, the vehicle and the parameters as an estimate would and estimates
// nothing: a fleet asks it whether a vehicle's parameters still hold before any log arrives.
TEST(EstimateTool, ChecksTheModelTheVehicleAndTheParametersWithoutALog) {
  const std::filesystem::path dir = freshDirectory("check");
  const std::string good = (dir / "good.yaml").string(), typo = (dir / "typo.yaml").string();
  std::ofstream(good) << "hover:\n  window_s: 3\n";
  std::ofstream(typo) << "hover:\n  windw_s: 3\n";
  const ToolRun accepted = runTool(PE_ESTIMATE, kModel + " --frame quad_x --arm-m 0.225 --params " + quoted(good) + " --check", dir);
  EXPECT_EQ(accepted.status, 0) << accepted.err;
  EXPECT_NE(accepted.out.find("  hover: window_s 3,"), std::string::npos) << accepted.out;
  EXPECT_NE(accepted.out.find("estimate: --check: " + repoPath("config/e300_dji2212_dji9443.yaml") +
                              ", the vehicle and " + good + " accepted\n"),
            std::string::npos)
      << accepted.out;
  const ToolRun refused = runTool(PE_ESTIMATE, kModel + " --params " + quoted(typo) + " --check", dir);
  EXPECT_EQ(refused.status, 1);
  EXPECT_EQ(refused.err, "estimate: " + typo + ": hover/windw_s: unknown parameter (see the README's parameter table)\n");
  // Usage errors (exit 2): --check beside what it does not read, and what an estimate needs.
  const std::vector<std::pair<std::string, std::string>> usage = {
      {" --check a.ulg", "estimate: logs excludes --check (see --help)\n"},
      {" --out " + quoted((dir / "out").string()),
       "estimate: logs: at least one flight log is required (or --check) (see --help)\n"},
      {" a.ulg", "estimate: --out is required (or --check) (see --help)\n"},
      {" --check --out " + quoted((dir / "out").string()), "estimate: --out excludes --check (see --help)\n"},
  };
  for (const auto& [arguments, err] : usage) {
    const ToolRun run = runTool(PE_ESTIMATE, kModel + arguments, dir);
    EXPECT_EQ(run.status, 2) << arguments;
    EXPECT_EQ(run.err, err) << arguments;
  }
  // The session is made: a model whose motor reference is a hexacopter's is refused for a quad.
  const std::string hexa = (dir / "hexa.yaml").string();
  std::ofstream(hexa) << slurp(repoPath("config/e300_dji2212_dji9443.yaml"))
                      << "motor_reference: {flights: 3, shares: [0.15, 0.15, 0.15, 0.15, 0.2, 0.2], share_std: [0.001, "
                         "0.001, 0.001, 0.001, 0.001, 0.001], gap_std: [0.002, 0.002, 0.002, 0.002, 0.002, 0.002]}\n";
  const ToolRun mismatched = runTool(PE_ESTIMATE, "--model " + quoted(hexa) + " --frame quad_x --arm-m 0.225 --check", dir);
  EXPECT_EQ(mismatched.status, 1);
  EXPECT_NE(mismatched.err.find("6 shares for 4 rotors"), std::string::npos) << mismatched.err;
}

// A rosbag damaged part-way, as a ULog or DataFlash log: a chunk whose compressed data is corrupt
// ends the flight there and the hovers before it are estimated, the reader's line among the
// warnings (the log named once); a bag cut short or never closed is refused with the remedy.
TEST(EstimateTool, EstimatesABagUpToItsDamageAndNamesTheRemedyForOneCutShort) {
  const std::filesystem::path dir = freshDirectory("damaged_bag");
  const std::string demo = slurp(repoPath("config/demo/demo_flight.bag"));
  ASSERT_GT(demo.size(), 1000000u);
  std::string corrupt = demo;
  corrupt.replace(corrupt.size() / 2, 64, std::string(64, '\xff'));
  const std::string corrupt_path = (dir / "corrupt.bag").string();
  std::ofstream(corrupt_path, std::ios::binary) << corrupt;
  const std::string cut_path = (dir / "cut.bag").string();
  std::ofstream(cut_path, std::ios::binary) << demo.substr(0, demo.size() / 2);
  const ToolRun run = runTool(PE_ESTIMATE,
                              kModel + " --no-figures --out " + quoted((dir / "out").string()) + " " +
                                  quoted(corrupt_path) + " " + quoted(cut_path),
                              dir);
  EXPECT_EQ(run.status, 1) << run.err;
  EXPECT_NE(run.out.find("estimated 1 of 2 logs"), std::string::npos) << run.out;
  const std::string damage = "  " + corrupt_path + ": reading failed after ";
  const std::size_t at = run.out.find(damage);
  ASSERT_NE(at, std::string::npos) << run.out;
  const std::string line = run.out.substr(at, run.out.find('\n', at) - at);
  EXPECT_NE(line.find(" s: data integrity error was detected in the compressed data (read up to there)"),
            std::string::npos)
      << line;
  EXPECT_NE(slurp(dir / "out/corrupt/summary.md").find("| 1 | "), std::string::npos) << "a hover before the damage";
  EXPECT_NE(run.err.find("estimate: " + cut_path + ": not a readable bag: at byte "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("beyond the file's end (" + std::to_string(demo.size() / 2) +
                         " bytes); `rosbag reindex` rebuilds its index from the whole records\n"),
            std::string::npos)
      << run.err;
}

// A log that ends within its format's first bytes is that format's log cut short, not a stranger.
TEST(EstimateTool, NamesTheFormatOfALogCutWithinItsFirstBytes) {
  const std::filesystem::path dir = freshDirectory("cut_signature");
  const std::string log = (dir / "log171.bin").string();
  std::ofstream(log, std::ios::binary) << slurp(repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin")).substr(0, 3);
  const ToolRun run = runTool(PE_ESTIMATE, kModel + " --no-figures --out " + quoted((dir / "out").string()) + " " + quoted(log), dir);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.err, "estimate: " + log + ": a dataflash log cut short: it ends after 3 bytes, within its first 5 "
                     "(\"\\xa3\\x95\\x80\\x80Y\")\n");
}

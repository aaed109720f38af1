// estimate as a user runs it: on the public PX4 and ArduPilot logs in test/data, with a log that
// does not exist among them, and with options it refuses.
#include <filesystem>
#include <fstream>
#include <string>

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

TEST(EstimateTool, RefusesASampleRateOutsideItsRangeNamingTheOption) {
  const std::filesystem::path dir = freshDirectory("rate");
  const ToolRun run = runTool(PE_ESTIMATE,
                              kModel + " --no-figures --sample-rate-hz -1 --out " + quoted((dir / "out").string()) +
                                  " " + quoted(repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin")),
                              dir);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.err, "estimate: --sample-rate-hz: -1 is outside 0..1000 Hz\n");
}

TEST(EstimateTool, RefusesAFrameWithoutItsArmLength) {
  const std::filesystem::path dir = freshDirectory("frame");
  const ToolRun run = runTool(PE_ESTIMATE,
                              kModel + " --no-figures --frame hexa_x --out " + quoted((dir / "out").string()) + " " +
                                  quoted(repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin")),
                              dir);
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.err, "estimate: --frame hexa_x: needs --arm-m, the arm length in m\n");
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

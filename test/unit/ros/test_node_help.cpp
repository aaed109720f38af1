// estimator_node run by hand: --help answers without a ROS master.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tool_process.h"

// --help says where the node's settings are and exits, with no ROS master to wait for.
TEST(EstimatorNode, HelpNamesItsParametersAndLaunchFileWithoutAMaster) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "pe_node_help";
  std::filesystem::create_directories(dir);
  const ToolRun run = runTool(PE_ESTIMATOR_NODE, "--help", dir);
  std::filesystem::remove_all(dir);
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.out.rfind("estimator_node: the propulsion estimator as a ROS node.", 0), 0u) << run.out;
  EXPECT_NE(run.out.find("roslaunch propulsion_estimator estimator.launch model:=MODEL.yaml"), std::string::npos);
  EXPECT_EQ(run.err, "");
}

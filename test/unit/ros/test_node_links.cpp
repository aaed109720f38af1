#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

// The shared libraries in `ldd` output that estimator_node must not load: rosbag, and the fitting,
// the gap diagnosis, the bag adapters, the tools and the simulator, none of which runs on the vehicle.
std::vector<std::string> forbiddenLibraries(const std::string& ldd_output) {
  const std::regex forbidden(R"(lib(rosbag[a-z_]*|propulsion_estimator_(fitting|gap|bag|apps|sim_[a-z]+))\.so)");
  std::vector<std::string> found;
  std::istringstream lines(ldd_output);
  std::string line;
  while (std::getline(lines, line)) {
    if (std::regex_search(line, forbidden)) found.push_back(line);
  }
  return found;
}

std::string lddOf(const std::string& binary, int* status) {
  FILE* pipe = popen(("ldd '" + binary + "' 2>&1").c_str(), "r");
  if (!pipe) {
    *status = -1;
    return "";
  }
  std::string output;
  char buffer[4096];
  std::size_t read = 0;
  while ((read = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, read);
  *status = pclose(pipe);
  return output;
}

}  // namespace

// The node links the ROS libraries it uses by name: even where the linker keeps every library it is
// given (the sanitizer build), rosbag, fitting and simulator code are not loaded on the vehicle.
TEST(NodeLinks, EstimatorNodeLoadsNoRosbagFittingOrSimulatorLibrary) {
  int status = 0;
  const std::string ldd = lddOf(PE_ESTIMATOR_NODE, &status);
  ASSERT_EQ(status, 0) << "ldd " << PE_ESTIMATOR_NODE << ":\n" << ldd;
  for (const std::string& line : forbiddenLibraries(ldd)) ADD_FAILURE() << "estimator_node loads" << line;
  // The check means something: the modules are shared libraries, which ldd lists.
  EXPECT_NE(ldd.find("libpropulsion_estimator_estimation.so"), std::string::npos) << ldd;
  EXPECT_NE(ldd.find("libroscpp.so"), std::string::npos) << ldd;
}

TEST(NodeLinks, CheckerFlagsRosbagFittingAndSimulator) {
  const std::string ldd =
      "\tlibroscpp.so.1d => /usr/lib/x86_64-linux-gnu/libroscpp.so.1d (0x00007f)\n"
      "\tlibrosbag_storage.so.1d => /usr/lib/x86_64-linux-gnu/librosbag_storage.so.1d (0x00007f)\n"
      "\tlibpropulsion_estimator_estimation.so => /ws/devel/lib/libpropulsion_estimator_estimation.so (0x00007f)\n"
      "\tlibpropulsion_estimator_fitting.so => /ws/devel/lib/libpropulsion_estimator_fitting.so (0x00007f)\n"
      "\tlibpropulsion_estimator_sim_physics.so => not found\n";
  const std::vector<std::string> found = forbiddenLibraries(ldd);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_NE(found[0].find("librosbag_storage"), std::string::npos);
  EXPECT_NE(found[1].find("fitting"), std::string::npos);
  EXPECT_NE(found[2].find("sim_physics"), std::string::npos);
  EXPECT_TRUE(forbiddenLibraries("\tlibtopic_tools.so => /usr/lib/libtopic_tools.so (0x1)\n").empty());
}

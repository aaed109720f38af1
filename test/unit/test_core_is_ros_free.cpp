#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "test_paths.h"

// The core library is what benchmarks, fuzzers and offline tools reuse: it must not include ROS.
TEST(CoreIsRosFree, NoRosHeaderIncluded) {
  const std::regex ros_include(
      R"(#include\s*[<"](ros|rosbag|topic_tools|diagnostic_updater|[a-z_]+_msgs|[a-z_]+_srvs)/)");
  int files = 0;
  for (const char* dir : {"include/propulsion_estimator/core", "src/core"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(repoPath(dir))) {
      if (!entry.is_regular_file()) continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      int number = 0;
      while (std::getline(in, line)) {
        ++number;
        EXPECT_FALSE(std::regex_search(line, ros_include)) << entry.path() << ":" << number << ": " << line;
      }
    }
  }
  EXPECT_GT(files, 10);
}

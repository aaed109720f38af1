#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "test_paths.h"

namespace {

// Which module may include which (besides itself): exactly the arrows the code has. The picture
// of the package: common is the leaf; model, vehicle and estimation are what runs on the vehicle and
// is replayed offline, onboard what only the node uses; logs, fitting and sim are the offline tools'
// core; ros and bag adapt ROS; apps holds every main and command line.
const std::map<std::string, std::set<std::string>> kMayInclude = {
    {"common", {}},
    {"model", {"common"}},
    {"vehicle", {"common"}},
    {"estimation", {"common", "model", "vehicle"}},
    {"onboard", {"common", "model", "estimation"}},
    {"logs", {"common"}},
    {"fitting", {"common", "model", "logs"}},
    {"gap", {"common", "model", "vehicle", "estimation", "logs"}},
    {"sim/physics", {"common"}},
    {"sim/stand", {"common", "logs", "sim/physics"}},
    {"sim/flight", {"common", "vehicle", "logs", "sim/physics"}},
    {"ros", {"common", "model", "vehicle", "estimation", "onboard"}},
    {"bag", {"common", "gap", "sim/flight", "ros"}},
    {"apps", {"common", "model", "vehicle", "logs", "fitting", "gap", "sim/physics", "sim/stand", "sim/flight",
              "ros", "bag"}},
};
// Modules that may include ROS headers.
const std::set<std::string> kRosModules = {"ros", "bag", "apps"};

// The module a path below include/propulsion_estimator/ or src/ belongs to: its first folder, or
// its first two for sim/.
std::string moduleOf(const std::string& relative) {
  const auto slash = relative.find('/');
  if (slash == std::string::npos) return "";
  const std::string first = relative.substr(0, slash);
  if (first != "sim") return first;
  const auto second = relative.find('/', slash + 1);
  return second == std::string::npos ? "" : relative.substr(0, second);
}

struct Violation {
  std::string where;
  std::string line;
};

}  // namespace

TEST(Layering, EveryModuleIncludesOnlyWhatItMay) {
  const std::regex own_include(R"re(#include\s*"propulsion_estimator/([a-z_/]+)/[a-z0-9_]+\.h")re");
  const std::regex ros_include(
      R"(#include\s*[<"](ros|rosbag|topic_tools|diagnostic_updater|[a-z_]+_msgs|[a-z_]+_srvs)/)");
  const std::regex message_include(R"re(#include\s*"propulsion_estimator/[A-Z][A-Za-z]+\.h")re");
  int files = 0;
  std::vector<Violation> violations;
  for (const std::string root : {"include/propulsion_estimator", "src"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(repoPath(root))) {
      if (!entry.is_regular_file()) continue;
      const std::string relative = std::filesystem::relative(entry.path(), repoPath(root)).generic_string();
      const std::string module = moduleOf(relative);
      ASSERT_TRUE(kMayInclude.count(module)) << root << "/" << relative << " is in no module of the table";
      ++files;
      const std::set<std::string>& allowed = kMayInclude.at(module);
      const bool ros_allowed = kRosModules.count(module) > 0;
      std::ifstream in(entry.path());
      std::string line;
      int number = 0;
      while (std::getline(in, line)) {
        ++number;
        std::smatch match;
        const std::string where = root + "/" + relative + ":" + std::to_string(number);
        if (std::regex_search(line, match, own_include)) {
          const std::string included = moduleOf(match[1].str() + "/x.h");
          if (included != module && !allowed.count(included)) violations.push_back({where, line});
        }
        if (!ros_allowed && (std::regex_search(line, ros_include) || std::regex_search(line, message_include))) {
          violations.push_back({where, line});
        }
      }
    }
  }
  for (const Violation& violation : violations) ADD_FAILURE() << violation.where << ": " << violation.line;
  EXPECT_GT(files, 90);
}

// The table itself has no cycle: a module never reaches itself through what it may include.
TEST(Layering, TableHasNoCycle) {
  for (const auto& [module, allowed] : kMayInclude) {
    std::set<std::string> reached(allowed.begin(), allowed.end());
    std::vector<std::string> pending(allowed.begin(), allowed.end());
    while (!pending.empty()) {
      const std::string next = pending.back();
      pending.pop_back();
      ASSERT_TRUE(kMayInclude.count(next)) << module << " may include unknown module " << next;
      for (const std::string& further : kMayInclude.at(next)) {
        if (reached.insert(further).second) pending.push_back(further);
      }
    }
    EXPECT_FALSE(reached.count(module)) << module << " reaches itself";
  }
}

// A rule that could not fail would prove nothing: the checker flags a forbidden include.
TEST(Layering, ModuleOfNamesTheFolder) {
  EXPECT_EQ(moduleOf("estimation/estimator.h"), "estimation");
  EXPECT_EQ(moduleOf("sim/flight/flight_simulator.cpp"), "sim/flight");
  EXPECT_EQ(moduleOf("estimator.h"), "");
  EXPECT_FALSE(kMayInclude.at("estimation").count("sim/physics"));
  EXPECT_FALSE(kMayInclude.at("ros").count("fitting"));
}

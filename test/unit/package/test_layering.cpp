#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_paths.h"

namespace {

// Which module may include which (besides itself): exactly the arrows the code has, checked both
// ways (an include the table does not allow, an arrow the table allows that no include uses), and
// the only links CMake may make between the modules' libraries. The picture of the package: common
// is the leaf; model, vehicle and estimation are what runs on the vehicle and is replayed offline,
// onboard what only the node uses; offline runs the node's session on a logged flight (estimate, and
// gap's replays of the onboard checks); logs, fitting, gap and sim are the offline tools' core; ros and bag adapt ROS; apps holds every main and command line.
using Graph = std::map<std::string, std::set<std::string>>;
const Graph kMayInclude = {
    {"common", {}},
    {"model", {"common"}},
    {"vehicle", {"common"}},
    {"estimation", {"common", "model", "vehicle"}},
    {"onboard", {"common", "model", "estimation"}},
    {"logs", {"common"}},
    {"fitting", {"common", "model", "logs"}},
    {"offline", {"common", "model", "vehicle", "estimation", "onboard", "logs"}},
    {"gap", {"common", "model", "vehicle", "estimation", "onboard", "logs", "offline"}},
    {"sim/physics", {"common"}},
    {"sim/stand", {"common", "logs", "sim/physics"}},
    {"sim/flight", {"common", "vehicle", "logs", "sim/physics"}},
    {"codecs", {"onboard"}},
    {"ros", {"common", "model", "vehicle", "onboard", "codecs"}},
    {"bag", {"common", "logs", "codecs", "sim/flight"}},
    {"apps", {"common", "model", "vehicle", "onboard", "logs", "offline", "fitting", "gap", "sim/physics", "sim/stand", "sim/flight", "ros",
              "bag"}},
};
// Modules that may include ROS headers.
const std::set<std::string> kRosModules = {"codecs", "ros", "bag", "apps"};

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

// What the sources say: the arrows their includes draw, and the includes the table forbids.
struct IncludeScan {
  Graph used;
  std::vector<Violation> violations;
  int files = 0;
};

IncludeScan scanIncludes() {
  const std::regex own_include(R"re(#include\s*"propulsion_estimator/([a-z_/]+)/[a-z0-9_]+\.h")re");
  const std::regex ros_include(
      R"(#include\s*[<"](ros|rosbag|topic_tools|diagnostic_updater|[a-z_]+_msgs|[a-z_]+_srvs)/)");
  const std::regex message_include(R"re(#include\s*"propulsion_estimator/[A-Z][A-Za-z]+\.h")re");
  IncludeScan scan;
  for (const std::string root : {"include/propulsion_estimator", "src"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(repoPath(root))) {
      if (!entry.is_regular_file()) continue;
      const std::string relative = std::filesystem::relative(entry.path(), repoPath(root)).generic_string();
      const std::string module = moduleOf(relative);
      if (!kMayInclude.count(module)) {
        scan.violations.push_back({root + "/" + relative, "is in no module of the table"});
        continue;
      }
      ++scan.files;
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
          if (included != module) scan.used[module].insert(included);
          if (included != module && !allowed.count(included)) scan.violations.push_back({where, line});
        }
        if (!ros_allowed && (std::regex_search(line, ros_include) || std::regex_search(line, message_include))) {
          scan.violations.push_back({where, line});
        }
      }
    }
  }
  return scan;
}

// "a -> b" for every arrow of `arrows` that `other` lacks: the table's arrows no include uses
// (missingArrows(table, used)), or the links the table does not allow (missingArrows(links, table)).
std::vector<std::string> missingArrows(const Graph& arrows, const Graph& other) {
  std::vector<std::string> missing;
  for (const auto& [module, targets] : arrows) {
    for (const std::string& to : targets) {
      if (!other.count(module) || !other.at(module).count(to)) missing.push_back(module + " -> " + to);
    }
  }
  return missing;
}

// The links between the modules' libraries in CMake code: pe_module(<library> <folder> <links>...)
// declares a module and its links, target_link_libraries(<library> [PUBLIC|PRIVATE|INTERFACE] ...)
// adds links. Other targets (executables, tests, the core interface) are not modules.
Graph cmakeModuleLinks(const std::string& cmake) {
  const std::string code = std::regex_replace(cmake, std::regex("#[^\n]*"), "");
  const std::regex declaration(R"(\bpe_module\s*\(([^)]*)\))");
  const std::regex link(R"(\btarget_link_libraries\s*\(([^)]*)\))");
  const auto words = [](const std::string& text) {
    std::istringstream in(text);
    return std::vector<std::string>(std::istream_iterator<std::string>(in), std::istream_iterator<std::string>());
  };
  std::map<std::string, std::string> folder_of;  // library -> module
  std::vector<std::pair<std::string, std::vector<std::string>>> links;
  for (std::sregex_iterator it(code.begin(), code.end(), declaration), end; it != end; ++it) {
    const std::vector<std::string> args = words((*it)[1].str());
    if (args.size() < 2) continue;
    folder_of[args[0]] = args[1];
    links.emplace_back(args[0], std::vector<std::string>(args.begin() + 2, args.end()));
  }
  for (std::sregex_iterator it(code.begin(), code.end(), link), end; it != end; ++it) {
    const std::vector<std::string> args = words((*it)[1].str());
    if (!args.empty()) links.emplace_back(args[0], std::vector<std::string>(args.begin() + 1, args.end()));
  }
  Graph graph;
  for (const auto& [library, linked] : links) {
    if (!folder_of.count(library)) continue;
    for (const std::string& other : linked) {
      if (folder_of.count(other)) graph[folder_of.at(library)].insert(folder_of.at(other));
    }
  }
  return graph;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST(Layering, EveryModuleIncludesOnlyWhatItMay) {
  const IncludeScan scan = scanIncludes();
  for (const Violation& violation : scan.violations) ADD_FAILURE() << violation.where << ": " << violation.line;
  EXPECT_GT(scan.files, 90);
}

// An arrow the table allows and no include uses is a dependency the picture claims and the code
// does not have.
TEST(Layering, EveryArrowOfTheTableIsUsed) {
  for (const std::string& arrow : missingArrows(kMayInclude, scanIncludes().used)) {
    ADD_FAILURE() << "the table allows " << arrow << " but no include uses it";
  }
}

// CMake links a module's library only to modules the table lets it include.
TEST(Layering, CMakeLinksOnlyArrowsOfTheTable) {
  const Graph links = cmakeModuleLinks(readFile(repoPath("cmake/pe_modules.cmake")) + "\n" +
                                       readFile(repoPath("CMakeLists.txt")));
  for (const std::string& arrow : missingArrows(links, kMayInclude)) {
    ADD_FAILURE() << "CMake links " << arrow << ", which the table does not allow";
  }
  // The parser read the real files: every module but common links another.
  EXPECT_EQ(links.size(), kMayInclude.size() - 1);
  EXPECT_TRUE(links.count("gap") && links.at("gap").count("offline"));
  EXPECT_TRUE(links.count("bag") && links.at("bag").count("codecs"));
  EXPECT_FALSE(links.at("bag").count("ros"));
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

// The two-way checks flag a bad case: an arrow no include uses, a link the table forbids.
TEST(Layering, CheckersFlagUnusedArrowsAndForbiddenLinks) {
  const Graph table = {{"a", {}}, {"b", {"a"}}, {"c", {"a", "b"}}};
  EXPECT_EQ(missingArrows(table, {{"b", {"a"}}, {"c", {"a"}}}), std::vector<std::string>{"c -> b"});
  EXPECT_TRUE(missingArrows(table, {{"b", {"a"}}, {"c", {"a", "b"}}}).empty());
  const Graph links = cmakeModuleLinks(
      "function(pe_module name folder)\nendfunction()\n"
      "pe_module(lib_a a)\npe_module(lib_b b lib_a)  # b uses a\n"
      "pe_module(lib_c c\n  lib_b)\ntarget_link_libraries(lib_a PUBLIC lib_c other)\n"
      "# target_link_libraries(lib_b PUBLIC lib_c)\nadd_executable(tool main.cpp)\ntarget_link_libraries(tool lib_c)\n");
  EXPECT_EQ(links, (Graph{{"a", {"c"}}, {"b", {"a"}}, {"c", {"b"}}}));
  EXPECT_EQ(missingArrows(links, table), std::vector<std::string>{"a -> c"});
}

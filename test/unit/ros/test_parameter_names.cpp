#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "parameter_template.h"
#include "propulsion_estimator/common/input_signal.h"
#include "test_paths.h"

namespace {

std::string readRepoFile(const std::string& relative) {
  std::ifstream in(repoPath(relative));
  EXPECT_TRUE(in) << relative;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every name the node's parameter reader knows (src/onboard/node_parameters.cpp): those it
// spells, and each scalar input's topic and timeout (input_signal.h).
std::set<std::string> readerParameters() {
  const std::string source = readRepoFile("src/onboard/node_parameters.cpp");
  const std::regex call(R"re(read\.(required|optional)\("([^"]+)")re");
  std::set<std::string> names;
  for (auto it = std::sregex_iterator(source.begin(), source.end(), call); it != std::sregex_iterator(); ++it) {
    names.insert((*it)[2].str());
  }
  for (propulsion_estimator::input::Scalar scalar : propulsion_estimator::input::kAllScalars) {
    names.insert(propulsion_estimator::input::topicParameter(scalar));
    names.insert(propulsion_estimator::input::timeoutParameter(scalar));
  }
  return names;
}

// Every name in the first column of the README's Parameters table ("`battery_topic`, `rc_out_topic`").
std::set<std::string> readmeParameters() {
  const std::string readme = readRepoFile("README.md");
  const std::size_t start = readme.find("### Parameters");
  EXPECT_NE(start, std::string::npos) << "README.md has no Parameters section";
  const std::size_t end = readme.find("\n### ", start + 1);
  std::istringstream section(readme.substr(start, end - start));
  const std::regex name("`([^`]+)`");
  std::set<std::string> names;
  std::string line;
  while (std::getline(section, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const std::string first_cell = line.substr(1, line.find('|', 1) - 1);
    for (auto it = std::sregex_iterator(first_cell.begin(), first_cell.end(), name); it != std::sregex_iterator();
         ++it) {
      names.insert((*it)[1].str());
    }
  }
  return names;
}

std::string listed(const std::set<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

// One spelling per parameter: the template, the reader and the README's table name the same ones.
TEST(ParameterNames, TemplateReaderAndReadmeAgree) {
  const ParameterTemplate file = loadParameterTemplate();
  std::set<std::string> in_template = file.commented;
  for (const auto& [name, value] : file.values) {
    EXPECT_TRUE(in_template.insert(name).second) << name << " is both set and commented in the template";
  }
  const std::set<std::string> in_reader = readerParameters();
  const std::set<std::string> in_readme = readmeParameters();
  EXPECT_GT(in_reader.size(), 25u) << listed(in_reader);
  EXPECT_EQ(in_template, in_reader) << "template: " << listed(in_template) << "\nreader: " << listed(in_reader);
  EXPECT_EQ(in_readme, in_reader) << "README: " << listed(in_readme) << "\nreader: " << listed(in_reader);
}

// The required model, the unset empty mass, battery, curve, pack file and the PWM top are shown,
// not set: a loaded template must neither point the node at a model nor invent an empty mass, a
// battery or a pack.
TEST(ParameterNames, TemplateSetsNeitherTheModelNorAnEmptyMass) {
  const ParameterTemplate file = loadParameterTemplate();
  EXPECT_EQ(file.commented, (std::set<std::string>{"capability/battery/capacity_ah", "capability/battery/cells",
                                                   "capability/battery/ocv_table/cell_v",
                                                   "capability/battery/ocv_table/soc", "capability/battery/pack_file",
                                                   "capability/battery/pack_id", "capability/battery/temperature_c",
                                                   "capability/pwm_max_us",
                                                   "empty_mass_kg", "model"}));
  EXPECT_EQ(file.values.count("model"), 0u);
  EXPECT_EQ(file.values.count("empty_mass_kg"), 0u);
}

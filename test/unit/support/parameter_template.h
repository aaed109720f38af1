#pragma once

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <yaml-cpp/yaml.h>

#include "test_paths.h"

// config/estimator_params.yaml, the commented template of estimator_node's parameters, as the
// node sees it once loaded into its private namespace: nested maps flattened to "hover/window_s".
struct ParameterTemplate {
  std::map<std::string, YAML::Node> values;  // set by the file
  std::set<std::string> commented;           // shown as "# name: example", not set (model, empty_mass_kg)
};

inline void flattenParameters(const YAML::Node& node, const std::string& prefix,
                              std::map<std::string, YAML::Node>* values) {
  for (const auto& entry : node) {
    const std::string name = prefix + entry.first.as<std::string>();
    if (entry.second.IsMap()) {
      flattenParameters(entry.second, name + "/", values);
    } else {
      (*values)[name] = entry.second;
    }
  }
}

inline ParameterTemplate loadParameterTemplate() {
  const std::string path = repoPath("config/estimator_params.yaml");
  ParameterTemplate result;
  flattenParameters(YAML::LoadFile(path), "", &result.values);
  // Prose in the file never starts a comment line with a lower-case word and a colon.
  const std::regex commented(R"(^#\s?([a-z][a-z_]*(/[a-z_]+)*):\s)");
  std::ifstream in(path);
  std::string line;
  std::smatch match;
  while (std::getline(in, line)) {
    if (std::regex_search(line, match, commented)) result.commented.insert(match[1].str());
  }
  return result;
}

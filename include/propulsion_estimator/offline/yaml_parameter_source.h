#pragma once

#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/onboard/parameter_source.h"

namespace propulsion_estimator {
namespace offline {

/// estimator_node's parameters from a YAML file of the keys a launch file loads into the node's
/// private namespace (config/estimator_params.yaml's layout: nested maps, "hover: {window_s: 2}" is
/// hover/window_s), for estimate. Messages name the file and the key ("params.yaml: hover/window_s").
class YamlParameterSource : public ParameterSource {
 public:
  /// Reads `path`; `set` adds or replaces top-level parameters (estimate's --model). Throws
  /// InputError naming the file when it cannot be read, and ConfigError "<path>: ..." when it is not
  /// YAML or its document is not a mapping.
  YamlParameterSource(const std::string& path, const std::map<std::string, std::string>& set);
  /// No file: only `set`, every other parameter at the node's default.
  explicit YamlParameterSource(const std::map<std::string, std::string>& set);

  /// ParameterSource's, over the file's leaves (yaml-cpp's conversions: "2" reads as a number).
  ///@{
  bool has(const std::string& name) const override;
  bool get(const std::string& name, std::string* value) const override;
  bool get(const std::string& name, double* value) const override;
  bool get(const std::string& name, bool* value) const override;
  bool get(const std::string& name, int* value) const override;
  bool get(const std::string& name, std::vector<int>* value) const override;
  bool get(const std::string& name, std::vector<double>* value) const override;
  std::vector<std::string> names() const override;
  std::string where(const std::string& name) const override;
  ///@}

 private:
  template <typename T>
  bool read(const std::string& name, T* value) const;

  std::string source_;
  std::map<std::string, YAML::Node> values_;  ///< by relative name, the leaves of the file's maps
};

}  // namespace offline
}  // namespace propulsion_estimator

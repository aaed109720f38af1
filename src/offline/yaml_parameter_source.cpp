#include "propulsion_estimator/offline/yaml_parameter_source.h"

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"

namespace propulsion_estimator {
namespace offline {
namespace {

// The leaves of nested maps by their slash-joined keys; a list is a leaf.
void flatten(const YAML::Node& node, const std::string& prefix, std::map<std::string, YAML::Node>* values) {
  for (const auto& entry : node) {
    const std::string name = prefix + entry.first.as<std::string>();
    if (entry.second.IsMap()) {
      flatten(entry.second, name + "/", values);
    } else {
      (*values)[name] = entry.second;
    }
  }
}

}  // namespace

YamlParameterSource::YamlParameterSource(const std::string& path, const std::map<std::string, std::string>& set)
    : source_(path) {
  const std::string text = readTextFile(path);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": not YAML: " + e.what());
  }
  if (!root.IsNull() && !root.IsMap()) throw ConfigError(path + ": expected a mapping of parameters");
  if (root.IsMap()) flatten(root, "", &values_);
  for (const auto& [name, value] : set) values_[name] = YAML::Node(value);
}

YamlParameterSource::YamlParameterSource(const std::map<std::string, std::string>& set) : source_("(defaults)") {
  for (const auto& [name, value] : set) values_[name] = YAML::Node(value);
}

bool YamlParameterSource::has(const std::string& name) const { return values_.count(name) != 0; }

template <typename T>
bool YamlParameterSource::read(const std::string& name, T* value) const {
  try {
    *value = values_.at(name).as<T>();
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

bool YamlParameterSource::get(const std::string& name, std::string* value) const {
  return values_.at(name).IsScalar() && read(name, value);
}
bool YamlParameterSource::get(const std::string& name, double* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, bool* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, int* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, std::vector<int>* value) const { return read(name, value); }
bool YamlParameterSource::get(const std::string& name, std::vector<double>* value) const {
  return read(name, value);
}

std::vector<std::string> YamlParameterSource::names() const {
  std::vector<std::string> names;
  for (const auto& entry : values_) names.push_back(entry.first);
  return names;
}

std::string YamlParameterSource::where(const std::string& name) const { return source_ + ": " + name; }

}  // namespace offline
}  // namespace propulsion_estimator

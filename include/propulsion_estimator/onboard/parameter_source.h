#pragma once

#include <string>
#include <vector>

namespace propulsion_estimator {

/// Where estimator_node's parameters come from, by their names relative to the node's private
/// namespace ("hover/window_s"): the ROS parameter server (ros/estimator_params.h) or a YAML file of
/// the same keys (offline/yaml_parameter_source.h, for estimate). Each get() is false when the
/// parameter is set with another type (a caller then refuses it); it is called only for a set name.
class ParameterSource {
 public:
  virtual ~ParameterSource() = default;

  virtual bool has(const std::string& name) const = 0;  ///< whether `name` is set
  virtual bool get(const std::string& name, std::string* value) const = 0;  ///< a string
  virtual bool get(const std::string& name, double* value) const = 0;  ///< a number; an integer reads as one
  virtual bool get(const std::string& name, bool* value) const = 0;  ///< true or false
  virtual bool get(const std::string& name, int* value) const = 0;  ///< an integer
  virtual bool get(const std::string& name, std::vector<int>* value) const = 0;  ///< a list of integers
  virtual bool get(const std::string& name, std::vector<double>* value) const = 0;  ///< a list of numbers
  /// Every parameter set, by its relative name, for refusing a misspelt one.
  virtual std::vector<std::string> names() const = 0;
  /// `name` as a message names it: "/propulsion_estimator/hover/window_s", "params.yaml: hover/window_s".
  virtual std::string where(const std::string& name) const = 0;
};

}  // namespace propulsion_estimator

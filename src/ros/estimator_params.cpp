#include "propulsion_estimator/ros/estimator_params.h"

#include <ros/console.h>

namespace propulsion_estimator {
namespace {

// The parameter server under the node's private namespace.
class RosParameterSource : public ParameterSource {
 public:
  explicit RosParameterSource(const ros::NodeHandle& nh) : nh_(nh) {}

  bool has(const std::string& name) const override { return nh_.hasParam(name); }
  bool get(const std::string& name, std::string* value) const override { return nh_.getParam(name, *value); }
  bool get(const std::string& name, double* value) const override { return nh_.getParam(name, *value); }
  bool get(const std::string& name, bool* value) const override { return nh_.getParam(name, *value); }
  bool get(const std::string& name, int* value) const override { return nh_.getParam(name, *value); }
  bool get(const std::string& name, std::vector<int>* value) const override { return nh_.getParam(name, *value); }
  bool get(const std::string& name, std::vector<double>* value) const override { return nh_.getParam(name, *value); }
  std::vector<std::string> names() const override {
    const std::string prefix = nh_.getNamespace() + "/";
    std::vector<std::string> all, mine;
    nh_.getParamNames(all);
    for (const std::string& name : all) {
      if (name.rfind(prefix, 0) == 0) mine.push_back(name.substr(prefix.size()));
    }
    return mine;
  }
  std::string where(const std::string& name) const override { return nh_.resolveName(name); }

 private:
  const ros::NodeHandle& nh_;
};

}  // namespace

EstimatorNodeParams readEstimatorNodeParams(const ros::NodeHandle& nh) {
  EstimatorNodeParams params = readNodeParameters(RosParameterSource(nh));
  ROS_INFO_STREAM(describeNodeParameters(params));
  return params;
}

}  // namespace propulsion_estimator

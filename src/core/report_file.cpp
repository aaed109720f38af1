#include "propulsion_estimator/core/report_file.h"

#include "propulsion_estimator/core/config_error.h"

namespace propulsion_estimator {

std::ofstream openReportFile(const std::string& directory, const std::string& name) {
  const std::string path = directory + "/" + name;
  std::ofstream file(path);
  if (!file) throw ConfigError(path + ": cannot open for writing");
  return file;
}

}  // namespace propulsion_estimator

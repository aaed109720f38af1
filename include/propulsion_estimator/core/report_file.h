#pragma once

#include <fstream>
#include <string>

namespace propulsion_estimator {

// A file of a report directory (Markdown, CSV), opened for writing; ConfigError naming the path
// when it cannot be.
std::ofstream openReportFile(const std::string& directory, const std::string& name);

}  // namespace propulsion_estimator

#include "propulsion_estimator/logs/file_pattern.h"

#include <glob.h>

namespace propulsion_estimator {

bool isFilePattern(const std::string& path) { return path.find_first_of("*?[") != std::string::npos; }

std::vector<std::string> matchingFiles(const std::string& pattern) {
  std::vector<std::string> files;
  glob_t found{};
  if (glob(pattern.c_str(), 0, nullptr, &found) == 0) {
    for (std::size_t i = 0; i < found.gl_pathc; ++i) files.emplace_back(found.gl_pathv[i]);
  }
  globfree(&found);
  return files;
}

}  // namespace propulsion_estimator

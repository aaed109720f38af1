#include "propulsion_estimator/common/text_file.h"

#include <sstream>

#include "propulsion_estimator/common/input_error.h"

namespace propulsion_estimator {

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read file");
  return content.str();
}

void writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open for writing");
  file << text;
  file.close();
  if (!file) throw InputError(path + ": cannot write");
}

std::ofstream openReportFile(const std::string& directory, const std::string& name) {
  const std::string path = directory + "/" + name;
  std::ofstream file(path);
  if (!file) throw InputError(path + ": cannot open for writing");
  return file;
}

}  // namespace propulsion_estimator

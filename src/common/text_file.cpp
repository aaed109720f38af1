#include "propulsion_estimator/common/text_file.h"

#include <filesystem>
#include <sstream>

#include "propulsion_estimator/common/input_error.h"

namespace propulsion_estimator {

void requireRegularFile(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::is_regular_file(status)) return;
  if (std::filesystem::is_directory(status)) throw InputError(path + ": a folder, not a file");
  if (std::filesystem::exists(status)) throw InputError(path + ": not a regular file (a device, pipe or socket)");
  throw InputError(path + ": no such file");
}

std::string readTextFile(const std::string& path) {
  // A folder opens as a stream whose size reads as the largest offset: refused by name instead.
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(path + ": a folder, not a file");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path + ": cannot open file");
  // Read at once into a string of the file's size: a stream that grows as it reads copies a
  // large log several times over (an hour of ULog is 50 MB).
  const std::streamoff size = in.tellg();
  if (size > 0) {
    std::string content(static_cast<std::size_t>(size), '\0');
    in.seekg(0);
    in.read(content.data(), static_cast<std::streamsize>(size));
    if (in.bad()) throw InputError(path + ": cannot read file");
    content.resize(static_cast<std::size_t>(in.gcount()));
    return content;
  }
  // No size (a pipe, a file of the proc filesystem): read as it comes.
  in.clear();
  in.seekg(0);
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

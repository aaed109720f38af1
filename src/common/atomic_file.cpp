#include "propulsion_estimator/common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <random>
#include <system_error>

#include "propulsion_estimator/common/input_error.h"

namespace propulsion_estimator {
namespace {


/// "<path>: <what> not written: <step>: <strerror(errno)>", for a failed system call.
InputError systemError(const std::string& path, const std::string& what, const std::string& step) {
  return InputError(path + ": " + what + " not written: " + step + ": " + std::strerror(errno));
}

/// A temporary file name next to `path` that no other process or call uses: process id, a
/// per-process counter and a random number (two containers may share the folder and the pid).
std::string temporaryName(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  static const unsigned random = std::random_device{}();
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
         std::to_string(random);
}

/// Writes the whole of `text` to the new file `temporary` and flushes it to the disk.
void writeDurably(const std::string& path, const std::string& what, const std::string& temporary,
                  const std::string& text) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw systemError(path, what, "cannot create a temporary file next to it");
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const InputError error = systemError(path, what, "cannot write the temporary file");
      ::close(fd);
      throw error;
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const InputError error = systemError(path, what, "cannot flush the temporary file to the disk");
    ::close(fd);
    throw error;
  }
  if (::close(fd) != 0) throw systemError(path, what, "cannot close the temporary file");
}

}  // namespace

void writeFileAtomically(const std::string& path, const std::string& text, const std::string& what) {
  const std::filesystem::path target(path);
  const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  const std::string temporary = temporaryName(path);
  try {
    writeDurably(path, what, temporary, text);
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
      throw systemError(path, what, "cannot replace it with the temporary file");
    }
  } catch (const InputError&) {
    ::unlink(temporary.c_str());
    throw;
  }
  // The rename itself made durable; a folder that cannot be opened or synced leaves it to the kernel.
  const int directory = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (directory >= 0) {
    ::fsync(directory);
    ::close(directory);
  }
}

std::vector<std::string> removeStaleTemporaries(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : ".";
  const std::string prefix = target.filename().string() + ".tmp-";
  std::vector<std::string> removed;
  std::error_code error;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator entry(folder, error), end; !error && entry != end; entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    std::error_code entry_error;
    const auto written = fs::last_write_time(entry->path(), entry_error);
    if (entry_error || std::chrono::duration<double>(now - written).count() <= kStaleTemporaryAgeS) continue;
    if (fs::remove(entry->path(), entry_error) && !entry_error) removed.push_back(entry->path().string());
  }
  return removed;
}

}  // namespace propulsion_estimator

#pragma once

#include <fstream>
#include <string>

namespace propulsion_estimator {

/// Throws InputError naming `path` unless it is a regular file: "<path>: no such file", "<path>:
/// a folder, not a file", "<path>: not a regular file (a device, pipe or socket)".
void requireRegularFile(const std::string& path);
/// The whole content of a file; InputError naming it when it cannot be read.
std::string readTextFile(const std::string& path);
/// Writes `text` as the whole content of a file; InputError naming it when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);

/// A file of a report directory (Markdown, CSV), opened for writing; InputError naming the path
/// when it cannot be.
std::ofstream openReportFile(const std::string& directory, const std::string& name);

}  // namespace propulsion_estimator

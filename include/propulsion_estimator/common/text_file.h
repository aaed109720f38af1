#pragma once

#include <fstream>
#include <string>

namespace propulsion_estimator {

/// The whole content of a file; InputError naming it when it cannot be read.
std::string readTextFile(const std::string& path);
/// Writes `text` as the whole content of a file; InputError naming it when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);

/// A file of a report directory (Markdown, CSV), opened for writing; InputError naming the path
/// when it cannot be.
std::ofstream openReportFile(const std::string& directory, const std::string& name);

}  // namespace propulsion_estimator

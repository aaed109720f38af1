#pragma once

#include <string>
#include <vector>

namespace propulsion_estimator {

/// Whether `path` is a shell pattern (holds *, ? or [) rather than one file's name.
bool isFilePattern(const std::string& path);

/// The files the shell pattern `pattern` matches, in name order, spelt as the pattern is (relative
/// when it is); empty when none does.
std::vector<std::string> matchingFiles(const std::string& pattern);

}  // namespace propulsion_estimator

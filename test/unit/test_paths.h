#pragma once

#include <string>

// Paths of the repository and of ../shared (real data, CI and development only), resolved by
// CMake from the repository's real path.
inline std::string repoPath(const std::string& relative) { return std::string(PE_REPO_DIR) + "/" + relative; }
inline std::string sharedPath(const std::string& relative) { return std::string(PE_SHARED_DIR) + "/" + relative; }

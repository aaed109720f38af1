#pragma once

#include <string>

// Paths in the repository, resolved by CMake from its real path. Tests read only what the
// repository holds (public data copied into test/data/ with its licence), nothing beside it.
inline std::string repoPath(const std::string& relative) { return std::string(PE_REPO_DIR) + "/" + relative; }

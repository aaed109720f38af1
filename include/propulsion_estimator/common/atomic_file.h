#pragma once

#include <string>
#include <vector>

namespace propulsion_estimator {

/// Writes `text` to `path` atomically, so that a crash never leaves half a file and two processes
/// never write into each other's: a temporary file of a name unique to this call (pid, counter,
/// random) next to `path` is written, fsynced and renamed over `path`, then the folder is fsynced;
/// missing folders are made. InputError "<path>: <what> not written: <step>: <reason>" when it
/// cannot be (the temporary file removed). `what` names the file's kind ("tare file").
void writeFileAtomically(const std::string& path, const std::string& text, const std::string& what);

/// A write takes milliseconds: a temporary file older than this was left by a process killed
/// while it wrote.
constexpr double kStaleTemporaryAgeS = 60.0;

/// Removes the temporary files of writeFileAtomically() next to `path` ("<path>.tmp-...") older
/// than kStaleTemporaryAgeS, and returns their names. A file that cannot be removed is left (and
/// not returned); never throws.
std::vector<std::string> removeStaleTemporaries(const std::string& path);

}  // namespace propulsion_estimator

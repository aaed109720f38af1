#pragma once

#include <optional>
#include <string>
#include <vector>

namespace propulsion_estimator {

/// The tare survives a restart of the node in a small YAML file:
/// @code{.yaml}
/// empty_mass_kg: 1.3154
/// model: <model file the tare was taken with>
/// model_fingerprint: <modelFingerprint() of that model>
/// @endcode
/// A tare is only meaningful with the model it was measured through: the fingerprint tells
/// whether the model now loaded is that one, wherever its file lies; the path is for people.
struct TareRecord {
  double empty_mass_kg = 0.0;  ///< kg
  std::string model;  ///< the model file the tare was taken with, for people
  std::string model_fingerprint;  ///< modelFingerprint() of that model
};

/// The tare in a tare file's text; ConfigError naming `source` for content that is not a tare.
TareRecord parseTareFile(const std::string& text, const std::string& source);
/// The tare in `path`; nullopt when the file does not exist. ConfigError naming the file for
/// content that is not a tare (InputError when it cannot be read).
std::optional<TareRecord> loadTareFile(const std::string& path);
/// Writes atomically (writeFileAtomically()): a crash never leaves half a file. InputError naming
/// the file and the failed step when it cannot be written.
void saveTareFile(const std::string& path, const TareRecord& record);
/// Removes the temporary files of saveTareFile() next to `path` that a killed write left
/// (removeStaleTemporaries()), and returns their names; never throws.
std::vector<std::string> removeStaleTareTemporaries(const std::string& path);
/// Removes the file if it exists and returns whether it did; InputError naming it when it exists
/// and cannot be removed.
bool removeTareFile(const std::string& path);
/// The tare a node starts with (TareAtStart).
struct TareAtStart {
  std::optional<TareRecord> record;  ///< nullopt when there is none or it was refused
  /// "" or "refused: <why>; started without the tare", and ", the file moved to <aside>" (or why it
  /// could not be) when it was moved aside.
  std::string refusal;
};
/// The tare in `path` at a node's start, never stopping it: content that is not a tare
/// (ConfigError) is moved aside (setAsideTareFile) for the next ~tare; a file that cannot be read
/// (a folder, no permission) is the user's and is left where it is, as the pack file keeper does.
/// Throws nothing.
TareAtStart loadTareAtStart(const std::string& path, long long unix_time);
/// Moves a tare file that cannot be used out of the way, to "<path>.bad-<unix_time>", and returns
/// that name; InputError naming both when it cannot be moved.
std::string setAsideTareFile(const std::string& path, long long unix_time);

}  // namespace propulsion_estimator

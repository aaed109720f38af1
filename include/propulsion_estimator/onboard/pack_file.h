#pragma once

#include <optional>
#include <string>
#include <vector>

namespace propulsion_estimator {

/// What the node has learned of one battery pack from its flights, kept between flights in a
/// small YAML file (capability/battery/pack_file, docs/capability.md):
/// @code{.yaml}
/// pack_id: field-pack-07        # the pack's identity: capability/battery/pack_id or BatteryState.serial_number
/// cells: 3
/// flights: 2                    # flights learned from
/// capacity_ah: 3.71             # the charge between full and empty as flown (absent until a flight spans enough)
/// ocv_soc: [0.15, 0.2, ...]     # the pack's open-circuit curve over the charge flown (0..1, rising)
/// ocv_cell_v: [3.62, 3.68, ...] # V per cell
/// resistance_ohm: [0.021, 0.022] # the resistance identified on each flight, oldest first (ageing)
/// rest_offset_cell_v: 0.012     # how far the pack rests above its loaded curve (absent until learned)
/// @endcode
struct PackRecord {
  std::string pack_id;  ///< the pack's identity; never empty in a file
  int cells = 0;        ///< in series, 1..14
  int flights = 0;      ///< flights learned from
  std::optional<double> capacity_ah;  ///< Ah
  std::vector<double> ocv_soc;        ///< 0..1, increasing; empty until learned
  std::vector<double> ocv_cell_v;     ///< V per cell, increasing, one per ocv_soc
  std::vector<double> resistance_ohm;  ///< ohm; one per flight that identified it, oldest first
  /// V per cell the pack rests above its learned (loaded) curve: the polarisation a hover builds,
  /// read at the landings (absent until learned).
  std::optional<double> rest_offset_cell_v;
};

/// The record in a pack file's text. ConfigError "<source>:<line>: <key>: <problem>" for content
/// that is not one: an unknown or missing key, an empty pack_id, cells outside 1..14, a negative
/// flight count, a capacity not positive, a curve whose lists differ in length, do not rise or
/// leave 0..1 and 2..4.5 V a cell, a resistance negative.
PackRecord parsePackFile(const std::string& text, const std::string& source);
/// The file's text for `record` (numbers to the last bit, so that it reads back identical).
std::string packFileText(const PackRecord& record);
/// The record in `path`; nullopt when the file does not exist. ConfigError naming the file for
/// content that is not a pack record (InputError when it cannot be read).
std::optional<PackRecord> loadPackFile(const std::string& path);
/// Writes atomically (writeFileAtomically()): a process killed while it writes leaves the former
/// record or the new one, never a mix. InputError naming the file and the failed step.
void savePackFile(const std::string& path, const PackRecord& record);

/// The pack file of pack `pack_id` under the parameter `pattern`: each "{pack_id}" in it replaced
/// by the identity (one file per pack), or the pattern itself (one file, whose record must then be
/// this pack's: see packFileRecordFor()).
std::string packFilePath(const std::string& pattern, const std::string& pack_id);

/// What a pack file holds for the pack flown now.
struct PackFileLookup {
  std::optional<PackRecord> record;  ///< the pack's record; nullopt when there is none to use
  /// Whether the file may be written with this pack's record (false: it holds another pack's).
  bool writable = true;
  std::string note;  ///< one line for the log and the diagnostics
};
/// Reads `path` for pack `pack_id` of `cells` cells: its record when the file holds this pack;
/// none, and not writable, when it holds another pack or another cell count (a flight never reads
/// or overwrites another pack's record); none and writable when there is no file. ConfigError or
/// InputError as loadPackFile().
PackFileLookup packFileRecordFor(const std::string& path, const std::string& pack_id, int cells);

}  // namespace propulsion_estimator

#pragma once

#include <optional>
#include <string>

#include "propulsion_estimator/onboard/pack_file.h"

namespace propulsion_estimator {

/// The node's pack file (capability/battery/pack_file) across a run: which pack is flown, its
/// record read once, each finished flight's record written atomically. ROS-free; never throws:
/// what went wrong is in note(), and the node goes on without the file.
class PackFileKeeper {
 public:
  /// `pattern`: the parameter ("" = off; "{pack_id}" in it makes a file per pack); `cells`: the
  /// configured pack's.
  PackFileKeeper(std::string pattern, int cells);

  bool enabled() const { return !pattern_.empty(); }  ///< a pack_file is configured
  bool identified() const { return !pack_id_.empty(); }  ///< identify() has been called
  /// Whether finished flights are written: identified, and the file is this pack's or absent.
  bool active() const { return identified() && writable_; }
  /// Whether the file was refused at identify() (moved aside or not) or the last save() failed.
  bool refused() const { return refused_; }

  /// The pack flown is `pack_id` (capability/battery/pack_id, or BatteryState.serial_number): reads
  /// its file. Returns its record when the file holds this pack; nullopt when there is none yet, it
  /// holds another pack (then never written), or it cannot be read (moved aside to
  /// "<file>.bad-<unix_time>" when its content is not a pack record, then learned afresh).
  std::optional<PackRecord> identify(const std::string& pack_id, long long unix_time);
  /// The record a finished flight is learned on top of: the file's, or a fresh one of this pack.
  const PackRecord& previous() const { return record_; }
  /// Writes `record` (previous() with a flight learned) and keeps it as previous(); returns the
  /// line to log (what was learned, or why it was not written).
  std::string save(const PackRecord& record);
  /// What the file said at identify() or at the last save(), for the diagnostics.
  const std::string& note() const { return note_; }
  /// The file of the pack identified ("" before identify()).
  const std::string& path() const { return path_; }

 private:
  std::string pattern_;
  int cells_;
  std::string pack_id_, path_, note_;
  bool writable_ = false;
  bool refused_ = false;
  PackRecord record_;
};

}  // namespace propulsion_estimator

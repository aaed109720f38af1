#include "propulsion_estimator/onboard/pack_file_keeper.h"

#include <filesystem>
#include <system_error>
#include <utility>

#include "propulsion_estimator/common/atomic_file.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {

PackFileKeeper::PackFileKeeper(std::string pattern, int cells) : pattern_(std::move(pattern)), cells_(cells) {}

std::optional<PackRecord> PackFileKeeper::identify(const std::string& pack_id, long long unix_time) {
  if (!enabled() || pack_id.empty()) return std::nullopt;
  pack_id_ = pack_id;
  path_ = packFilePath(pattern_, pack_id);
  record_ = PackRecord{};
  record_.pack_id = pack_id;
  record_.cells = cells_;
  writable_ = true;
  refused_ = false;
  note_.clear();
  for (const std::string& stale : removeStaleTemporaries(path_)) note_ += "removed " + stale + " (a write killed); ";
  try {
    PackFileLookup lookup = packFileRecordFor(path_, pack_id, cells_);
    note_ += lookup.note;
    writable_ = lookup.writable;
    if (lookup.record) record_ = *lookup.record;
    return lookup.record;
  } catch (const ConfigError& e) {
    const std::string aside = path_ + ".bad-" + std::to_string(unix_time);
    std::error_code error;
    std::filesystem::rename(path_, aside, error);
    note_ += std::string("refused: ") + e.what() +
             (error ? "; not moved aside (" + error.message() + "), not written" : "; moved to " + aside +
                                                                                        ", learned afresh");
    writable_ = !error;
    refused_ = true;
  } catch (const InputError& e) {
    note_ += std::string("refused: ") + e.what() + "; not written";
    writable_ = false;
    refused_ = true;
  }
  return std::nullopt;
}

std::string PackFileKeeper::save(const PackRecord& record) {
  if (!active()) return path_ + ": not written (" + note_ + ")";
  try {
    savePackFile(path_, record);
  } catch (const InputError& e) {
    note_ = e.what();
    refused_ = true;
    return note_;
  }
  record_ = record;
  refused_ = false;
  note_ = path_ + ": pack \"" + record.pack_id + "\", " + std::to_string(record.flights) + " flights learned";
  std::string line = note_;
  if (record.capacity_ah) line += ", capacity " + formatPrintf("%.3f Ah", *record.capacity_ah);
  if (!record.resistance_ohm.empty()) {
    line += ", resistance " + formatPrintf("%.1f mOhm", 1000.0 * record.resistance_ohm.back());
  }
  line += ", curve over " + std::to_string(record.ocv_soc.size()) + " points";
  return line;
}

}  // namespace propulsion_estimator

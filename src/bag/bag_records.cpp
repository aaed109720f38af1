#include "propulsion_estimator/bag/bag_records.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>

namespace propulsion_estimator {
namespace {

constexpr std::uint8_t kBagHeaderOp = 0x03, kIndexDataOp = 0x04, kChunkOp = 0x05, kChunkInfoOp = 0x06,
                       kConnectionOp = 0x07;
constexpr double kMaxCompressionRatio = 1000.0;
constexpr std::uint64_t kMaxChunkBytes = 1ull << 30;

// Walks a record header's fields (each a 4-byte length and "name=value"), calling use(name, value)
// for each; false when they do not exactly fill it: rosbag's header parser reads past the header
// when a field's length does not fit.
template <class Use>
bool forEachField(const char* header, std::uint64_t size, Use use) {
  std::uint64_t at = 0;
  while (at < size) {
    std::uint32_t length = 0;
    if (size - at < 4) return false;
    std::memcpy(&length, header + at, 4);
    at += 4;
    if (length > size - at) return false;
    const std::string_view field(header + at, length);
    const std::size_t equals = field.find('=');
    if (equals != std::string_view::npos) use(field.substr(0, equals), field.substr(equals + 1));
    at += length;
  }
  return true;
}

bool fieldsFit(const char* header, std::uint64_t size) {
  return forEachField(header, size, [](std::string_view, std::string_view) {});
}

// A header's one-byte op, or -1 when it has none; nullopt when its fields do not fit.
std::optional<int> headerOp(const char* header, std::uint64_t size) {
  int op = -1;
  const bool fit = forEachField(header, size, [&](std::string_view name, std::string_view value) {
    if (name == "op") op = value.size() == 1 ? static_cast<std::uint8_t>(value[0]) : -1;
  });
  return fit ? std::optional<int>(op) : std::nullopt;
}

// A record header's fields, by name (call on a header whose fields fit).
std::map<std::string, std::string> headerFields(const std::string& header) {
  std::map<std::string, std::string> fields;
  forEachField(header.data(), header.size(), [&](std::string_view name, std::string_view value) {
    fields[std::string(name)] = std::string(value);
  });
  return fields;
}

// A little-endian integer field of 4 or 8 bytes; `fallback` when absent or of another size.
std::uint64_t number(const std::map<std::string, std::string>& fields, const char* name, std::uint64_t fallback) {
  const auto field = fields.find(name);
  if (field == fields.end() || (field->second.size() != 4 && field->second.size() != 8)) return fallback;
  std::uint64_t value = 0;
  std::memcpy(&value, field->second.data(), field->second.size());
  return value;
}

// Walks the file's records, keeping what later records point at: rosbag follows the bag header's
// index position, the chunk infos' chunk positions and the index entries' offsets into a chunk
// without checking them.
class BagWalker {
 public:
  explicit BagWalker(const std::string& path) : in_(path, std::ios::binary) {
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
    in_.seekg(0);
  }

  BagRecordCheck check() {
    const std::string damage = walk();
    return {damage, !damage.empty() && !bag_header_damaged_};
  }

 private:
  std::string walk() {
    // The version line read as rosbag reads it (sscanf, trailing bytes ignored); 2.0 is walked here.
    std::string line;
    std::getline(in_, line);
    std::string name(line.size() + 1, '\0');  // room for any word of the line
    int major = 0, minor = 0;
    if (!in_ || std::sscanf(line.c_str(), "#ROS%s V%d.%d", &name[0], &major, &minor) != 3 || major != 2 || minor != 0) {
      return "";  // rosbag reads or refuses it
    }
    const std::uint64_t bag_header = line.size() + 1;
    std::uint64_t at = bag_header;
    while (at < size_) {
      const std::uint64_t record = at;
      bag_header_damaged_ = record == bag_header;
      std::string header, problem;
      std::uint32_t data_length = 0;
      if (!readLength(&at, "header", &problem) || !readBytes(&at, &header) ||
          !readLength(&at, "data", &problem, &data_length)) {
        return "at byte " + std::to_string(record) + ": " + (problem.empty() ? "record truncated" : problem);
      }
      record_starts_.insert(record);
      if (!fieldsFit(header.data(), header.size())) return "at byte " + std::to_string(record) + ": malformed header";
      problem = checkRecord(record, headerFields(header), at, data_length);
      if (!problem.empty()) return "at byte " + std::to_string(record) + ": " + problem;
      at += data_length;
      in_.seekg(static_cast<std::streamoff>(at));
    }
    bag_header_damaged_ = false;
    if (index_pos_ != 0 && record_starts_.count(index_pos_) == 0 && index_pos_ != size_) {
      return "the bag header's index position " + std::to_string(index_pos_) + " is not a record's start";
    }
    // rosbag reads as many records as the counts say, wherever they end: past the last record it
    // reads a length from whatever bytes follow. (An index position of 0 is an unindexed bag,
    // which rosbag refuses itself.)
    const std::uint64_t indexed = index_connections_ + index_chunks_;
    if (index_pos_ != 0 && indexed > 0 && recordsFrom(index_pos_) < indexed) {
      return "the bag header states " + std::to_string(index_connections_) + " connections and " +
             std::to_string(index_chunks_) + " chunks at byte " + std::to_string(index_pos_) + ", but only " +
             std::to_string(recordsFrom(index_pos_)) + " records lie there";
    }
    for (const auto& [chunk, connections] : chunk_connections_) {
      const std::uint64_t after = recordsFrom(chunk) - 1;
      if (after < connections) {
        return "the chunk at byte " + std::to_string(chunk) + " lists " + std::to_string(connections) +
               " connections, but only " + std::to_string(after) + " records follow it";
      }
    }
    return "";
  }

  // Records from the one at `at` (included) to the file's end; 0 when none starts there.
  std::uint64_t recordsFrom(std::uint64_t at) const {
    const auto first = record_starts_.find(at);
    return first == record_starts_.end() ? 0 : static_cast<std::uint64_t>(std::distance(first, record_starts_.end()));
  }

  bool readLength(std::uint64_t* at, const char* what, std::string* problem, std::uint32_t* out = nullptr) {
    std::uint32_t length = 0;
    if (size_ - *at < 4) return false;
    in_.read(reinterpret_cast<char*>(&length), 4);
    *at += 4;
    if (length > size_ - *at) {
      *problem = std::string("record ") + what + " of " + std::to_string(length) + " bytes, beyond the file's end (" +
                 std::to_string(size_) + " bytes)";
      return false;
    }
    pending_ = length;
    if (out) *out = length;
    return true;
  }
  bool readBytes(std::uint64_t* at, std::string* bytes) {
    bytes->assign(pending_, '\0');
    in_.read(&(*bytes)[0], pending_);
    *at += pending_;
    return true;
  }
  std::string data(std::uint64_t at, std::uint32_t length) {
    std::string bytes(length, '\0');
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(&bytes[0], length);
    return bytes;
  }

  std::string checkRecord(std::uint64_t record, const std::map<std::string, std::string>& fields, std::uint64_t at,
                          std::uint32_t data_length) {
    const auto op = fields.find("op");
    if (op == fields.end() || op->second.size() != 1) return "";  // rosbag refuses it
    switch (static_cast<std::uint8_t>(op->second[0])) {
      case kBagHeaderOp:
        index_pos_ = number(fields, "index_pos", 0);
        index_connections_ = number(fields, "conn_count", 0);
        index_chunks_ = number(fields, "chunk_count", 0);
        return "";
      case kChunkOp:
        chunk_starts_.insert(record);
        return checkChunk(fields, at, data_length);
      case kIndexDataOp:
        // rosbag reads `count` entries of 12 bytes, past the record's data if it says so.
        if (number(fields, "count", 0) > data_length / 12) {
          return "index record states " + std::to_string(number(fields, "count", 0)) + " entries in " +
                 std::to_string(data_length) + " bytes";
        }
        return checkIndex(data(at, data_length));
      case kConnectionOp: {
        const std::string connection = data(at, data_length);
        return fieldsFit(connection.data(), connection.size()) ? "" : "malformed connection header";
      }
      case kChunkInfoOp: {
        const std::uint64_t chunk = number(fields, "chunk_pos", 0);
        const std::uint64_t connections = number(fields, "count", 0);
        if (chunk_starts_.count(chunk) == 0) return "chunk info pointing at no chunk's start";
        // rosbag reads `count` (connection, messages) pairs of 8 bytes, then as many index records
        // after the chunk.
        if (connections > data_length / 8) {
          return "chunk info states " + std::to_string(connections) + " connections in " + std::to_string(data_length) +
                 " bytes";
        }
        chunk_connections_[chunk] = std::max(chunk_connections_[chunk], connections);
        return "";
      }
      default:
        return "";
    }
  }

  // A chunk's stated uncompressed size, and without compression the records inside it.
  std::string checkChunk(const std::map<std::string, std::string>& fields, std::uint64_t at,
                         std::uint32_t data_length) {
    const auto compression = fields.find("compression");
    chunk_size_ = number(fields, "size", 0);
    chunk_records_.clear();
    if (compression == fields.end()) return "";  // rosbag refuses it
    const bool none = compression->second == "none";
    if (none ? chunk_size_ != data_length
             : chunk_size_ > kMaxChunkBytes || chunk_size_ > kMaxCompressionRatio * data_length + 4096.0) {
      return "chunk of " + std::to_string(data_length) + " bytes (" + compression->second + ") states " +
             std::to_string(chunk_size_) + " bytes uncompressed";
    }
    chunk_walked_ = none;
    if (!none) return "";
    const std::string bytes = data(at, data_length);
    for (std::uint64_t inner = 0; inner < bytes.size();) {
      chunk_records_.insert(inner);
      std::uint64_t next = inner;
      bool connection = false;
      for (int part = 0; part < 2; ++part) {
        std::uint32_t length = 0;
        if (bytes.size() - next < 4) return "a record inside the chunk at offset " + std::to_string(inner) + " truncated";
        std::memcpy(&length, bytes.data() + next, 4);
        next += 4;
        if (length > bytes.size() - next) {
          return "a record inside the chunk at offset " + std::to_string(inner) + " runs past the chunk's end";
        }
        // Both parts of a connection record are headers; a message's data is the message.
        const bool header = part == 0 || connection;
        const std::optional<int> op = header ? headerOp(bytes.data() + next, length) : std::nullopt;
        if (header && !op) {
          return "a record inside the chunk at offset " + std::to_string(inner) + " has a malformed header";
        }
        if (part == 0) connection = *op == kConnectionOp;
        next += length;
      }
      inner = next;
    }
    return "";
  }

  // Index entries (time, offset into the preceding chunk) must point at one of its records.
  std::string checkIndex(const std::string& entries) {
    for (std::size_t at = 8; at + 4 <= entries.size(); at += 12) {
      std::uint32_t offset = 0;
      std::memcpy(&offset, entries.data() + at, 4);
      if (chunk_walked_ ? chunk_records_.count(offset) == 0 : offset >= chunk_size_) {
        return "index entry pointing at offset " + std::to_string(offset) + ", not a record of its chunk";
      }
    }
    return "";
  }

  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint32_t pending_ = 0;
  std::uint64_t index_pos_ = 0, index_connections_ = 0, index_chunks_ = 0;
  std::set<std::uint64_t> record_starts_, chunk_starts_, chunk_records_;
  std::map<std::uint64_t, std::uint64_t> chunk_connections_;  // chunk start -> connections its info lists
  std::uint64_t chunk_size_ = 0;
  bool chunk_walked_ = false;
  bool bag_header_damaged_ = false;  // the record walk() stopped at is the bag header
};

}  // namespace

BagRecordCheck checkBagRecords(const std::string& path) { return BagWalker(path).check(); }

}  // namespace propulsion_estimator

#include "propulsion_estimator/logs/dataflash_file.h"

#include <cstring>
#include <limits>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/logs/flight_log_reader.h"

namespace propulsion_estimator {
namespace dataflash {

const char kMagic[6] = {'\xa3', '\x95', '\x80', '\x80', 89, 0};

namespace {

constexpr std::uint8_t kFmt = 128;
constexpr std::size_t kFmtLength = 89;  // header 3, type 1, length 1, name 4, format 16, labels 64

template <typename T>
T load(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

// A fixed char field without its trailing NULs.
std::string text(const std::string& bytes, std::size_t at, std::size_t size) {
  std::string field = bytes.substr(at, size);
  return field.substr(0, field.find('\0'));
}

std::string hex(std::uint8_t byte) {
  static const char kHex[] = "0123456789abcdef";
  return std::string("0x") + kHex[byte >> 4] + kHex[byte & 0xf];
}

}  // namespace

std::size_t columnSize(char format) {
  switch (format) {
    case 'b': case 'B': case 'M': return 1;
    case 'h': case 'H': case 'c': case 'C': return 2;
    case 'i': case 'I': case 'f': case 'e': case 'E': case 'L': case 'n': return 4;
    case 'd': case 'q': case 'Q': return 8;
    case 'N': return 16;
    case 'Z': case 'a': return 64;
    default: return 0;
  }
}

File::File(std::string bytes, std::string source) : bytes_(std::move(bytes)), source_(std::move(source)) {
  if (bytes_.compare(0, 5, kMagic, 5) != 0) {
    throw DataError(source_ + ": not a DataFlash log (it does not start with the FMT message of FMT)");
  }
  parseMessages();
}

void File::parseMessages() {
  std::size_t at = 0;
  while (at < bytes_.size()) {
    const auto fail = [&](const std::string& what, const std::string& problem) {
      refusal_ = source_ + ": at byte " + std::to_string(at) + ": " + printableBytes(what) + ": " + printableBytes(problem);
    };
    if (at + 3 > bytes_.size()) return fail("message header", "truncated (" + std::to_string(bytes_.size() - at) + " of 3 bytes)");
    if (bytes_[at] != '\xa3' || bytes_[at + 1] != '\x95') {
      return fail("message header", "expected 0xa3 0x95, found " + hex(bytes_[at]) + " " + hex(bytes_[at + 1]));
    }
    const auto id = static_cast<std::uint8_t>(bytes_[at + 2]);
    const auto type = types_.find(id);
    const std::size_t length = id == kFmt ? kFmtLength : type == types_.end() ? 0 : type->second.length;
    const std::string name = id == kFmt ? "FMT" : type == types_.end() ? "type " + std::to_string(id) : type->second.name;
    if (length == 0) return fail(name, "no FMT message defined it");
    if (at + length > bytes_.size()) {
      return fail(name, "truncated (" + std::to_string(bytes_.size() - at) + " of " + std::to_string(length) + " bytes)");
    }
    std::string problem;
    if (id == kFmt && !parseFormat(at, &problem)) return fail(name, problem);
    messages_.push_back({id, at});
    at += length;
  }
}

bool File::parseFormat(std::size_t at, std::string* problem) {
  Type type;
  const auto id = static_cast<std::uint8_t>(bytes_[at + 3]);
  type.length = static_cast<std::uint8_t>(bytes_[at + 4]);
  type.name = text(bytes_, at + 5, 4);
  type.format = text(bytes_, at + 9, 16);
  const std::string labels = text(bytes_, at + 25, 64);
  for (std::size_t begin = 0; begin <= labels.size();) {
    std::size_t end = labels.find(',', begin);
    if (end == std::string::npos) end = labels.size();
    type.labels.push_back(labels.substr(begin, end - begin));
    begin = end + 1;
  }
  if (labels.empty()) type.labels.clear();
  if (type.labels.size() != type.format.size()) {
    *problem = type.name + ": " + std::to_string(type.format.size()) + " format characters for " +
               std::to_string(type.labels.size()) + " labels";
    return false;
  }
  std::size_t offset = 3;
  for (const char format : type.format) {
    const std::size_t size = columnSize(format);
    if (size == 0) {
      *problem = type.name + ": format character '" + std::string(1, format) + "' unknown";
      return false;
    }
    type.columns.push_back({offset, format});
    offset += size;
  }
  if (offset != type.length) {
    *problem = type.name + ": its columns take " + std::to_string(offset) + " bytes, its length says " +
               std::to_string(type.length);
    return false;
  }
  if (id == kFmt && type.length != kFmtLength) {
    *problem = "FMT redefined with length " + std::to_string(type.length);
    return false;
  }
  types_[id] = type;
  return true;
}

std::optional<std::uint8_t> File::typeNamed(const std::string& name) const {
  for (const auto& [id, type] : types_) {
    if (type.name == name) return id;
  }
  return std::nullopt;
}

std::optional<Column> File::column(std::uint8_t type, const std::string& label) const {
  const auto found = types_.find(type);
  if (found == types_.end()) return std::nullopt;
  for (std::size_t i = 0; i < found->second.labels.size(); ++i) {
    if (found->second.labels[i] == label) return found->second.columns[i];
  }
  return std::nullopt;
}

double File::value(const Message& message, const Column& column) const {
  const std::size_t at = message.offset + column.offset;
  switch (column.format) {
    case 'b': return load<std::int8_t>(bytes_, at);
    case 'B': case 'M': return load<std::uint8_t>(bytes_, at);
    case 'h': return load<std::int16_t>(bytes_, at);
    case 'H': return load<std::uint16_t>(bytes_, at);
    case 'c': return 0.01 * load<std::int16_t>(bytes_, at);
    case 'C': return 0.01 * load<std::uint16_t>(bytes_, at);
    case 'i': return load<std::int32_t>(bytes_, at);
    case 'I': return load<std::uint32_t>(bytes_, at);
    case 'e': return 0.01 * load<std::int32_t>(bytes_, at);
    case 'E': return 0.01 * load<std::uint32_t>(bytes_, at);
    case 'L': return 1e-7 * load<std::int32_t>(bytes_, at);
    case 'f': return load<float>(bytes_, at);
    case 'd': return load<double>(bytes_, at);
    case 'q': return static_cast<double>(load<std::int64_t>(bytes_, at));
    case 'Q': return static_cast<double>(load<std::uint64_t>(bytes_, at));
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace dataflash
}  // namespace propulsion_estimator

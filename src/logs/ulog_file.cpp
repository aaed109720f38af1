#include "propulsion_estimator/logs/ulog_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/logs/flight_log_reader.h"

namespace propulsion_estimator {
namespace ulog {

const char kMagic[8] = {'U', 'L', 'o', 'g', 0x01, 0x12, 0x35, 0};

namespace {

constexpr std::size_t kHeaderSize = 16;
constexpr std::size_t kMessageHeaderSize = 3;  // uint16 msg_size, uint8 msg_type
constexpr std::uint8_t kDataAppended = 0x01;   // incompat_flags[0], bit 0
constexpr int kMaxNesting = 8;

template <typename T>
T load(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

std::string trim(const std::string& text) {
  const std::size_t first = text.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(' ') - first + 1);
}

}  // namespace

std::size_t sizeOf(Primitive primitive) {
  switch (primitive) {
    case Primitive::kInt8: case Primitive::kUint8: case Primitive::kBool: case Primitive::kChar: return 1;
    case Primitive::kInt16: case Primitive::kUint16: return 2;
    case Primitive::kInt32: case Primitive::kUint32: case Primitive::kFloat: return 4;
    case Primitive::kInt64: case Primitive::kUint64: case Primitive::kDouble: return 8;
  }
  return 1;
}

std::optional<Primitive> primitiveNamed(const std::string& name) {
  static const std::map<std::string, Primitive> kNames = {
      {"int8_t", Primitive::kInt8},     {"uint8_t", Primitive::kUint8},   {"int16_t", Primitive::kInt16},
      {"uint16_t", Primitive::kUint16}, {"int32_t", Primitive::kInt32},   {"uint32_t", Primitive::kUint32},
      {"int64_t", Primitive::kInt64},   {"uint64_t", Primitive::kUint64}, {"float", Primitive::kFloat},
      {"double", Primitive::kDouble},   {"bool", Primitive::kBool},       {"char", Primitive::kChar}};
  const auto found = kNames.find(name);
  if (found == kNames.end()) return std::nullopt;
  return found->second;
}

File::File(std::string bytes, std::string source) : bytes_(std::move(bytes)), source_(std::move(source)) {
  parseHeader();
  parseMessages();
}

void File::parseHeader() {
  if (bytes_.size() < kHeaderSize || bytes_.compare(0, 7, kMagic, 7) != 0) {
    throw DataError(source_ + ": not a ULog (it does not start with the 16-byte ULog header)");
  }
  // The flag bits, when present, come first: an incompatible flag this reader does not know
  // refuses the file, as the format asks.
  if (bytes_.size() >= kHeaderSize + kMessageHeaderSize && bytes_[kHeaderSize + 2] == 'B') {
    const std::size_t size = load<std::uint16_t>(bytes_, kHeaderSize);
    const std::size_t at = kHeaderSize + kMessageHeaderSize;
    if (size < 40 || at + size > bytes_.size()) {
      throw DataError(source_ + ": at byte " + std::to_string(kHeaderSize) + ": B (flag bits): " +
                      std::to_string(size) + " bytes, expected 40 within the file");
    }
    for (int i = 0; i < 8; ++i) {
      const auto flags = static_cast<std::uint8_t>(bytes_[at + 8 + i]);
      const std::uint8_t known = i == 0 ? kDataAppended : 0;
      if ((flags & ~known) != 0) {
        throw DataError(source_ + ": at byte " + std::to_string(kHeaderSize) + ": B (flag bits): incompatible flag " +
                        std::to_string(i) + " = " + std::to_string(flags) + " unknown to this reader");
      }
    }
    if (static_cast<std::uint8_t>(bytes_[at + 8]) & kDataAppended) appended_offset_ = load<std::uint64_t>(bytes_, at + 16);
  }
}

void File::parseMessages() {
  // Most of a log is data messages, rarely under 24 bytes each with their header: room for all of
  // them at once, so that growing the index never copies it (an hour of ULog is a million).
  data_.reserve(bytes_.size() / 24);
  std::size_t at = kHeaderSize;
  bool appended = false;
  while (at < bytes_.size()) {
    // A log that was not closed may hold a partial message where the appended data begins.
    if (!appended && appended_offset_ > at && at + kMessageHeaderSize > appended_offset_) {
      at = appended_offset_;
      appended = true;
      continue;
    }
    if (at + kMessageHeaderSize > bytes_.size()) {
      refusal_ = source_ + ": at byte " + std::to_string(at) + ": message header: truncated (" +
                 std::to_string(bytes_.size() - at) + " of 3 bytes)";
      return;
    }
    const std::size_t size = load<std::uint16_t>(bytes_, at);
    const char type = bytes_[at + 2];
    const std::size_t payload = at + kMessageHeaderSize;
    if (!appended && appended_offset_ > at && payload + size > appended_offset_) {
      at = appended_offset_;
      appended = true;
      continue;
    }
    const std::string name = (type >= 0x20 && type < 0x7f) ? std::string(1, type) : "type " + std::to_string(+type);
    if (payload + size > bytes_.size()) {
      refusal_ = source_ + ": at byte " + std::to_string(at) + ": " + name + " message: truncated (" +
                 std::to_string(bytes_.size() - payload) + " of " + std::to_string(size) + " bytes)";
      return;
    }
    std::string problem;
    if (!parseMessage(type, payload, size, &problem)) {
      refusal_ = source_ + ": at byte " + std::to_string(at) + ": " + name + " message: " + printableBytes(problem);
      return;
    }
    at = payload + size;
  }
}

bool File::parseMessage(char type, std::size_t at, std::size_t size, std::string* problem) {
  switch (type) {
    case 'F':
      return parseFormat(bytes_.substr(at, size), problem);
    case 'I':
    case 'M': {
      const std::size_t skip = type == 'M' ? 1 : 0;
      if (size < skip + 1 || skip + 1 + static_cast<std::uint8_t>(bytes_[at + skip]) > size) {
        *problem = "key longer than the message";
        return false;
      }
      if (type == 'M' && bytes_[at] != 0) return true;  // a continuation: the first part is enough here
      const std::size_t key_size = static_cast<std::uint8_t>(bytes_[at + skip]);
      const std::string key = bytes_.substr(at + skip + 1, key_size);
      const std::size_t space = key.find(' ');
      const std::size_t value_at = at + skip + 1 + key_size;
      info_[space == std::string::npos ? key : key.substr(space + 1)] = bytes_.substr(value_at, at + size - value_at);
      return true;
    }
    case 'A': {
      if (size < 4) {
        *problem = std::to_string(size) + " bytes, fewer than the 4 of an empty subscription";
        return false;
      }
      Subscription subscription{trim(bytes_.substr(at + 3, size - 3)), static_cast<std::uint8_t>(bytes_[at])};
      if (!formats_.count(subscription.name)) {
        *problem = "subscribes to '" + subscription.name + "', which no format defines";
        return false;
      }
      subscriptions_[load<std::uint16_t>(bytes_, at + 1)] = subscription;
      return true;
    }
    case 'D': {
      if (size < 2 + 8) {
        *problem = std::to_string(size) + " bytes, too short for a msg_id and a timestamp";
        return false;
      }
      const auto msg_id = load<std::uint16_t>(bytes_, at);
      if (!subscriptions_.count(msg_id)) {
        *problem = "msg_id " + std::to_string(msg_id) + ", which no subscription (A message) announced";
        return false;
      }
      data_.push_back({msg_id, at + 2, size - 2});
      return true;
    }
    case 'O':
      if (size >= 2) {
        ++dropouts_;
        dropout_ms_ += load<std::uint16_t>(bytes_, at);
      }
      return true;
    default:
      // B, P, Q, R, L, C, S and types a newer logger may add: not needed, skipped by their size.
      return true;
  }
}

bool File::parseFormat(const std::string& text, std::string* problem) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || colon == 0) {
    *problem = "format '" + text.substr(0, 40) + "' has no 'name:'";
    return false;
  }
  Format format;
  format.name = text.substr(0, colon);
  std::size_t begin = colon + 1;
  while (begin < text.size()) {
    std::size_t end = text.find(';', begin);
    if (end == std::string::npos) end = text.size();
    const std::string item = trim(text.substr(begin, end - begin));
    begin = end + 1;
    if (item.empty()) continue;
    const std::size_t space = item.find(' ');
    if (space == std::string::npos) {
      *problem = format.name + ": field '" + item + "' is not 'type name'";
      return false;
    }
    Field field;
    std::string type = item.substr(0, space);
    field.name = trim(item.substr(space + 1));
    const std::size_t bracket = type.find('[');
    if (bracket != std::string::npos) {
      const std::string count = type.substr(bracket + 1, type.size() - bracket - 2);
      if (type.back() != ']' || count.empty() || count.size() > 5 ||
          count.find_first_not_of("0123456789") != std::string::npos || std::stoi(count) == 0) {
        *problem = format.name + ": field '" + item + "' has a bad array length";
        return false;
      }
      field.count = std::stoi(count);
      type = type.substr(0, bracket);
    }
    field.primitive = primitiveNamed(type);
    if (!field.primitive) field.nested = type;
    format.fields.push_back(field);
  }
  if (format.fields.empty()) {
    *problem = format.name + ": no fields";
    return false;
  }
  formats_[format.name] = format;
  // Nested types may be defined after the formats that use them: sizes are settled once all are
  // known, here for every format whose types are all defined by now.
  for (auto& [name, known] : formats_) {
    std::vector<std::string> resolving;
    std::string ignored;
    resolve(&known, &resolving, &ignored);
  }
  return true;
}

bool File::resolve(Format* format, std::vector<std::string>* resolving, std::string* problem) {
  if (format->size > 0) return true;
  if (std::find(resolving->begin(), resolving->end(), format->name) != resolving->end() ||
      resolving->size() > kMaxNesting) {
    *problem = format->name + ": nests itself";
    return false;
  }
  resolving->push_back(format->name);
  std::size_t offset = 0;
  for (Field& field : format->fields) {
    std::size_t element = 0;
    if (field.primitive) {
      element = sizeOf(*field.primitive);
    } else {
      const auto nested = formats_.find(field.nested);
      if (nested == formats_.end() || !resolve(&nested->second, resolving, problem)) return false;
      element = nested->second.size;
    }
    field.offset = offset;
    field.size = element * static_cast<std::size_t>(std::max(field.count, 1));
    offset += field.size;
    if (offset > std::numeric_limits<std::uint16_t>::max()) {
      *problem = format->name + ": larger than a message can be";
      return false;
    }
  }
  resolving->pop_back();
  format->size = offset;
  return true;
}

std::string File::infoText(const std::string& key) const {
  const auto found = info_.find(key);
  return found == info_.end() ? "" : found->second;
}

std::optional<Locator> File::locate(const std::string& format_name, const std::string& path) const {
  const Format* format = nullptr;
  const auto found = formats_.find(format_name);
  if (found == formats_.end() || found->second.size == 0) return std::nullopt;
  format = &found->second;
  std::size_t offset = 0;
  std::size_t begin = 0;
  for (int depth = 0; depth < kMaxNesting; ++depth) {
    std::size_t end = path.find('.', begin);
    if (end == std::string::npos) end = path.size();
    std::string part = path.substr(begin, end - begin);
    int index = -1;
    const std::size_t bracket = part.find('[');
    if (bracket != std::string::npos) {
      if (part.back() != ']') return std::nullopt;
      index = std::stoi(part.substr(bracket + 1, part.size() - bracket - 2));
      part = part.substr(0, bracket);
    }
    const auto field = std::find_if(format->fields.begin(), format->fields.end(),
                                    [&part](const Field& f) { return f.name == part; });
    if (field == format->fields.end() || (index >= 0) != (field->count > 0) || index >= field->count) {
      return std::nullopt;
    }
    const std::size_t element = field->size / static_cast<std::size_t>(std::max(field->count, 1));
    offset += field->offset + static_cast<std::size_t>(std::max(index, 0)) * element;
    if (end == path.size()) {
      if (!field->primitive) return std::nullopt;
      return Locator{offset, *field->primitive};
    }
    if (field->primitive) return std::nullopt;
    format = &formats_.at(field->nested);
    begin = end + 1;
  }
  return std::nullopt;
}

double File::value(const DataMessage& message, const Locator& locator) const {
  if (locator.offset + sizeOf(locator.primitive) > message.size) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t at = message.offset + locator.offset;
  switch (locator.primitive) {
    case Primitive::kInt8: return load<std::int8_t>(bytes_, at);
    case Primitive::kUint8: case Primitive::kChar: return load<std::uint8_t>(bytes_, at);
    case Primitive::kBool: return load<std::uint8_t>(bytes_, at) != 0;
    case Primitive::kInt16: return load<std::int16_t>(bytes_, at);
    case Primitive::kUint16: return load<std::uint16_t>(bytes_, at);
    case Primitive::kInt32: return load<std::int32_t>(bytes_, at);
    case Primitive::kUint32: return load<std::uint32_t>(bytes_, at);
    case Primitive::kInt64: return static_cast<double>(load<std::int64_t>(bytes_, at));
    case Primitive::kUint64: return static_cast<double>(load<std::uint64_t>(bytes_, at));
    case Primitive::kFloat: return load<float>(bytes_, at);
    case Primitive::kDouble: return load<double>(bytes_, at);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::uint64_t File::timestampUs(const DataMessage& message) const { return load<std::uint64_t>(bytes_, message.offset); }

}  // namespace ulog
}  // namespace propulsion_estimator

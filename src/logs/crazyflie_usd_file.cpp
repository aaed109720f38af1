#include "propulsion_estimator/logs/crazyflie_usd_file.h"

#include <cmath>
#include <cstring>
#include <map>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/logs/flight_log_reader.h"

namespace propulsion_estimator {
namespace crazyflie {

const char kMagic[4] = {'\xbc', 2, 0, 0};

namespace {

constexpr std::size_t kRecordHead = 10;  // uint16 event id, uint64 timestamp
constexpr std::size_t kCrcSize = 4;

template <typename T>
T load(const std::string& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

// An IEEE 754 half-precision value.
double halfToDouble(std::uint16_t bits) {
  const int exponent = (bits >> 10) & 0x1f;
  const int mantissa = bits & 0x3ff;
  double magnitude;
  if (exponent == 0) {
    magnitude = std::ldexp(mantissa, -24);  // subnormal
  } else if (exponent == 0x1f) {
    magnitude = mantissa == 0 ? HUGE_VAL : std::nan("");
  } else {
    magnitude = std::ldexp(mantissa + 1024, exponent - 25);
  }
  return (bits & 0x8000) ? -magnitude : magnitude;
}

double value(const std::string& bytes, std::size_t at, char type) {
  switch (type) {
    case 'B': return load<std::uint8_t>(bytes, at);
    case 'H': return load<std::uint16_t>(bytes, at);
    case 'I': return load<std::uint32_t>(bytes, at);
    case 'b': return load<std::int8_t>(bytes, at);
    case 'h': return load<std::int16_t>(bytes, at);
    case 'i': return load<std::int32_t>(bytes, at);
    case 'f': return load<float>(bytes, at);
    default: return halfToDouble(load<std::uint16_t>(bytes, at));  // 'e', the only other valueSize knows
  }
}

std::string hex32(std::uint32_t value) {
  static const char kHex[] = "0123456789abcdef";
  std::string text = "0x";
  for (int shift = 28; shift >= 0; shift -= 4) text += kHex[(value >> shift) & 0xf];
  return text;
}

}  // namespace

std::size_t valueSize(char type) {
  switch (type) {
    case 'B': case 'b': return 1;
    case 'H': case 'h': case 'e': return 2;
    case 'I': case 'i': case 'f': return 4;
    default: return 0;
  }
}

std::uint32_t crc32(const char* data, std::size_t size) {
  std::uint32_t crc = 0xffffffffu;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= static_cast<std::uint8_t>(data[i]);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::optional<std::size_t> Event::column(const std::string& name) const {
  for (std::size_t k = 0; k < variables.size(); ++k) {
    if (variables[k].name == name) return k;
  }
  return std::nullopt;
}

File::File(const std::string& bytes, std::string source) : source_(std::move(source)) {
  if (bytes.empty() || bytes[0] != kMagic[0]) {
    throw DataError(source_ + ": not a Crazyflie uSD log (it does not start with 0xbc)");
  }
  std::size_t at = 1;
  parseHeader(bytes, &at);
  parseRecords(bytes, at);
}

void File::parseHeader(const std::string& bytes, std::size_t* at) {
  const auto fail = [&](const std::string& problem) {
    throw DataError(source_ + ": at byte " + std::to_string(*at) + ": header: " + printableBytes(problem));
  };
  // The text from *at to its NUL, past the NUL; nothing when the bytes end first.
  const auto text = [&]() -> std::optional<std::string> {
    const std::size_t end = bytes.find('\0', *at);
    if (end == std::string::npos) return std::nullopt;
    std::string read = bytes.substr(*at, end - *at);
    *at = end + 1;
    return read;
  };
  const auto uint16 = [&]() -> std::optional<std::uint16_t> {
    if (bytes.size() - *at < 2) return std::nullopt;
    *at += 2;
    return load<std::uint16_t>(bytes, *at - 2);
  };
  const auto version = uint16();
  if (!version) fail("truncated in the version");
  if (*version != 2) {
    throw DataError(source_ + ": Crazyflie uSD log version " + std::to_string(*version) + ": only version 2 is read");
  }
  const auto types = uint16();
  if (!types) fail("truncated in the number of event types");
  // Each event type is read from the bytes there are: a declared count is never allocated ahead.
  for (int k = 1; k <= *types; ++k) {
    const std::string which = "event type " + std::to_string(k) + " of " + std::to_string(*types);
    Event event;
    const std::size_t start = *at;
    const auto id = uint16();
    const auto name = id ? text() : std::nullopt;
    const auto variables = name ? uint16() : std::nullopt;
    if (!variables) fail("truncated in " + which);
    event.id = *id;
    event.name = *name;
    for (const Event& known : events_) {
      if (known.id != event.id) continue;
      *at = start;
      fail("event " + event.name + ": id " + std::to_string(event.id) + " defined twice");
    }
    for (int v = 0; v < *variables; ++v) {
      const std::size_t variable = *at;
      const auto declared = text();
      if (!declared) fail("truncated in " + which + " (" + event.name + ")");
      const std::size_t size = declared->size();
      if (size < 4 || declared->compare(size - 3, 1, "(") != 0 || declared->back() != ')') {
        *at = variable;
        fail("event " + event.name + ": variable '" + *declared + "': not group.name(T)");
      }
      const char type = (*declared)[size - 2];
      if (valueSize(type) == 0) {
        *at = variable;
        fail("event " + event.name + ": variable '" + *declared + "': type character '" + std::string(1, type) +
             "' unknown (B, H, I, b, h, i, f, e)");
      }
      event.variables.push_back({declared->substr(0, size - 3), type});
      event.record_size += valueSize(type);
    }
    event.columns.resize(event.variables.size());
    events_.push_back(std::move(event));
  }
}

void File::parseRecords(const std::string& bytes, std::size_t at) {
  const auto fail = [&](const std::string& what, const std::string& problem) {
    refusal_ = source_ + ": at byte " + std::to_string(at) + ": " + printableBytes(what) + ": " + problem;
  };
  std::map<std::uint16_t, Event*> by_id;
  for (Event& event : events_) by_id[event.id] = &event;
  while (bytes.size() - at > kCrcSize) {
    const std::size_t left = bytes.size() - at;
    if (left < kRecordHead + kCrcSize) {
      return fail("record", "truncated (" + std::to_string(left) + " bytes left for a 10-byte record head and the 4-byte CRC)");
    }
    const auto id = load<std::uint16_t>(bytes, at);
    const auto found = by_id.find(id);
    if (found == by_id.end()) return fail("record", "event id " + std::to_string(id) + " not defined in the header");
    Event& event = *found->second;
    if (left < kRecordHead + event.record_size + kCrcSize) {
      return fail(event.name + " record", "truncated (" + std::to_string(left) + " bytes left for a record of " +
                                              std::to_string(kRecordHead + event.record_size) + " and the 4-byte CRC)");
    }
    event.timestamp_us.push_back(load<std::uint64_t>(bytes, at + 2));
    std::size_t offset = at + kRecordHead;
    for (std::size_t k = 0; k < event.variables.size(); ++k) {
      event.columns[k].push_back(value(bytes, offset, event.variables[k].type));
      offset += valueSize(event.variables[k].type);
    }
    at = offset;
  }
  if (bytes.size() - at < kCrcSize) {
    return fail("CRC-32", "truncated (" + std::to_string(bytes.size() - at) + " of 4 bytes)");
  }
  const std::uint32_t stored = load<std::uint32_t>(bytes, at);
  const std::uint32_t computed = crc32(bytes.data(), at);
  if (stored != computed) fail("CRC-32", "the file says " + hex32(stored) + ", its bytes give " + hex32(computed));
}

const Event* File::eventWith(const std::string& name) const {
  for (const Event& event : events_) {
    if (event.column(name)) return &event;
  }
  return nullptr;
}

}  // namespace crazyflie
}  // namespace propulsion_estimator

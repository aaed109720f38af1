#include "propulsion_estimator/logs/dataflash_writer.h"

#include <algorithm>
#include <stdexcept>

#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/logs/dataflash_file.h"

namespace propulsion_estimator {
namespace dataflash {
namespace {

constexpr std::uint8_t kFmt = 128;

BinaryPayload formatMessage(std::uint8_t id, std::size_t length, const std::string& name, const std::string& format,
                            const std::string& labels) {
  BinaryPayload payload;
  payload.put(id).put(static_cast<std::uint8_t>(length)).text(name, 4).text(format, 16).text(labels, 64);
  return payload;
}

}  // namespace

Writer::Writer() { write(kFmt, formatMessage(kFmt, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns")); }

void Writer::define(std::uint8_t id, const std::string& name, const std::string& format, const std::string& labels) {
  std::size_t length = 3;
  for (const char c : format) {
    if (columnSize(c) == 0) throw std::invalid_argument(name + ": format character '" + std::string(1, c) + "' unknown");
    length += columnSize(c);
  }
  if (static_cast<std::size_t>(std::count(labels.begin(), labels.end(), ',')) + 1 != format.size() ||
      name.size() > 4 || format.size() > 16 || labels.size() > 64 || length > 255) {
    throw std::invalid_argument(name + ": labels '" + labels + "' do not fit format '" + format + "'");
  }
  write(kFmt, formatMessage(id, length, name, format, labels));
}

void Writer::write(std::uint8_t id, const BinaryPayload& payload) {
  bytes_ += '\xa3';
  bytes_ += '\x95';
  bytes_ += static_cast<char>(id);
  bytes_ += payload.bytes();
}

void Writer::save(const std::string& path) const { writeTextFile(path, bytes_); }

}  // namespace dataflash
}  // namespace propulsion_estimator

#include "propulsion_estimator/logs/ulog_writer.h"

#include <stdexcept>

#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/logs/ulog_file.h"

namespace propulsion_estimator {
namespace ulog {

Writer::Writer(std::uint64_t start_us) {
  bytes_.assign(kMagic, 7);
  bytes_ += '\x01';  // file format version
  bytes_ += Payload().put(start_us).bytes();
}

void Writer::message(char type, const std::string& payload) {
  if (payload.size() > 0xffff) throw std::length_error("ULog message longer than 65535 bytes");
  bytes_ += Payload().put(static_cast<std::uint16_t>(payload.size())).put(type).bytes();
  bytes_ += payload;
}

void Writer::flagBits(std::uint64_t appended_offset) {
  Payload payload;
  payload.zeros(8);                                                        // compat_flags
  payload.put<std::uint8_t>(appended_offset > 0 ? 1 : 0).zeros(7);        // incompat_flags
  payload.put(appended_offset).put<std::uint64_t>(0).put<std::uint64_t>(0);  // appended_offsets
  message('B', payload.bytes());
}

void Writer::format(const std::string& definition) { message('F', definition); }

void Writer::info(const std::string& key, const std::string& value) {
  message('I', Payload().put(static_cast<std::uint8_t>(key.size())).bytes() + key + value);
}

void Writer::subscribe(std::uint16_t msg_id, const std::string& name, std::uint8_t multi_id) {
  message('A', Payload().put(multi_id).put(msg_id).bytes() + name);
}

void Writer::data(std::uint16_t msg_id, const Payload& payload) {
  message('D', Payload().put(msg_id).bytes() + payload.bytes());
}

void Writer::dropout(std::uint16_t duration_ms) { message('O', Payload().put(duration_ms).bytes()); }

void Writer::save(const std::string& path) const { writeTextFile(path, bytes_); }

}  // namespace ulog
}  // namespace propulsion_estimator

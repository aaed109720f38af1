#include "propulsion_estimator/logs/crazyflie_usd_writer.h"

#include <stdexcept>

#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/logs/crazyflie_usd_file.h"

namespace propulsion_estimator {
namespace crazyflie {

void Writer::define(std::uint16_t id, const std::string& name, const std::vector<std::string>& variables) {
  if (!records_.empty()) throw std::invalid_argument(name + ": defined after the first record");
  for (const Defined& known : defined_) {
    if (known.id == id) throw std::invalid_argument(name + ": event id " + std::to_string(id) + " defined twice");
  }
  BinaryPayload type;
  type.put(id);
  type.text(name + '\0', name.size() + 1);
  type.put(static_cast<std::uint16_t>(variables.size()));
  std::size_t record_size = 0;
  for (const std::string& variable : variables) {
    const std::size_t n = variable.size();
    if (n < 4 || variable[n - 3] != '(' || variable[n - 1] != ')' || valueSize(variable[n - 2]) == 0) {
      throw std::invalid_argument(name + ": variable '" + variable + "' is not group.name(T) with a known T");
    }
    record_size += valueSize(variable[n - 2]);
    type.text(variable + '\0', n + 1);
  }
  defined_.push_back({id, record_size});
  types_ += type.bytes();
}

void Writer::write(std::uint16_t id, std::uint64_t timestamp_us, const BinaryPayload& values) {
  for (const Defined& known : defined_) {
    if (known.id != id) continue;
    if (values.bytes().size() != known.record_size) {
      throw std::invalid_argument("event id " + std::to_string(id) + ": " + std::to_string(values.bytes().size()) +
                                  " bytes of values, its variables take " + std::to_string(known.record_size));
    }
    records_ += BinaryPayload().put(id).put(timestamp_us).bytes() + values.bytes();
    return;
  }
  throw std::invalid_argument("event id " + std::to_string(id) + " not defined");
}

std::string Writer::bytes() const {
  std::string log = BinaryPayload()
                        .put<std::uint8_t>(0xbc)
                        .put<std::uint16_t>(2)
                        .put(static_cast<std::uint16_t>(defined_.size()))
                        .bytes() +
                    types_ + records_;
  return log + BinaryPayload().put(crc32(log.data(), log.size())).bytes();
}

void Writer::save(const std::string& path) const { writeTextFile(path, bytes()); }

}  // namespace crazyflie
}  // namespace propulsion_estimator

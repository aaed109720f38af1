#pragma once

#include <algorithm>
#include <cstring>
#include <string>

namespace propulsion_estimator {

/// A binary log message's bytes, field by field, little-endian as ULog and DataFlash store them
/// (the host's order: this package builds for x86-64 and arm64 only).
class BinaryPayload {
 public:
  /// Appends `value`'s bytes (uint64_t, float, uint8_t, ...).
  template <typename T>
  BinaryPayload& put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    bytes_.append(bytes, sizeof(T));
    return *this;
  }
  /// Appends `count` zero bytes (padding, unused array elements).
  BinaryPayload& zeros(std::size_t count) {
    bytes_.append(count, '\0');
    return *this;
  }
  /// Appends `text`, cut or padded with zeros to `size` bytes (a fixed char field).
  BinaryPayload& text(const std::string& text, std::size_t size) {
    bytes_ += text.substr(0, size);
    return zeros(size - std::min(size, text.size()));
  }
  const std::string& bytes() const { return bytes_; }  ///< what has been appended

 private:
  std::string bytes_;
};

}  // namespace propulsion_estimator

#pragma once

#include <cstddef>
#include <vector>

namespace propulsion_estimator {

/// Samples of the last `span_s` seconds in a ring buffer allocated once: pushing evicts samples
/// older than the span and, when the buffer is full, the oldest one (the window then covers less
/// time, which its span() shows).
template <typename T>
class TimeWindow {
 public:
  TimeWindow(double span_s, std::size_t capacity) : span_s_(span_s), stamps_(capacity), values_(capacity) {}

  void push(double stamp_s, const T& value) {
    while (size_ > 0 && stamps_[head_] < stamp_s - span_s_) popOldest();
    if (size_ == stamps_.size()) popOldest();
    const std::size_t slot = (head_ + size_) % stamps_.size();
    stamps_[slot] = stamp_s;
    values_[slot] = value;
    ++size_;
  }

  void clear() { head_ = size_ = 0; }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  // Time between the oldest and the newest sample.
  double span() const { return size_ < 2 ? 0.0 : newestStamp() - stamps_[head_]; }
  double newestStamp() const { return stamps_[(head_ + size_ - 1) % stamps_.size()]; }
  // i = 0 is the oldest sample.
  const T& operator[](std::size_t i) const { return values_[(head_ + i) % values_.size()]; }

 private:
  void popOldest() {
    head_ = (head_ + 1) % stamps_.size();
    --size_;
  }

  double span_s_;
  std::vector<double> stamps_;
  std::vector<T> values_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace propulsion_estimator

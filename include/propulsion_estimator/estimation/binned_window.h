#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace propulsion_estimator {

/// Statistics of the samples of the last `span_s` seconds, at any sample rate in fixed memory:
/// samples are aggregated into kBins bins of span_s / kBins seconds, and the window keeps the
/// newest kBins bins, so it covers between (kBins - 1) / kBins of span_s and less than span_s.
/// Adding a sample costs O(1); starting a bin re-merges the closed bins (O(kBins)), once per
/// bin length whatever the rate.
///
/// `Aggregate` is a value type with `void add(const Sample&)` and `void merge(const Aggregate&)`,
/// and whose default value is the aggregate of no sample.
template <typename Aggregate>
class BinnedWindow {
 public:
  static constexpr std::size_t kBins = 64;  ///< bins per window

  /// `span_s` > 0 (validated by the owner's config).
  explicit BinnedWindow(double span_s) : bin_s_(span_s / static_cast<double>(kBins)) {}

  /// Adds a sample stamped `stamp_s` (s). Stamps are expected not to go back; one that does is
  /// counted in the newest bin.
  template <typename Sample>
  void add(double stamp_s, const Sample& sample) {
    const std::int64_t index = static_cast<std::int64_t>(std::floor(stamp_s / bin_s_));
    if (empty()) {
      startBin(index, stamp_s);
    } else if (index > newest_index_) {
      // Bins this far behind have left the window (their slots are reused as they come round).
      const std::int64_t oldest_kept = index - static_cast<std::int64_t>(kBins) + 1;
      if (oldest_index_ < oldest_kept) oldest_index_ = oldest_kept;
      startBin(index, stamp_s);
      mergeClosedBins();
    }
    Bin& bin = bins_[slot(newest_index_)];
    bin.aggregate.add(sample);
    newest_stamp_s_ = stamp_s;
    ++samples_;
  }

  /// The aggregate of every sample in the window.
  Aggregate total() const {
    Aggregate all = closed_;
    if (!empty()) all.merge(bins_[slot(newest_index_)].aggregate);
    return all;
  }

  /// Forgets every sample.
  void clear() {
    samples_ = 0;
    closed_ = Aggregate{};
    // A bin of before must not pass for one of after when the clock comes back to its index.
    for (Bin& bin : bins_) bin.index = kNoBin;
  }
  /// Whether the window holds no sample.
  bool empty() const { return samples_ == 0; }
  /// Time between the oldest and the newest sample in the window, s.
  double span() const { return empty() ? 0.0 : newest_stamp_s_ - bins_[slot(oldest_index_)].first_stamp_s; }
  /// Length of one bin, s: the resolution at which old samples leave the window.
  double binLength() const { return bin_s_; }

 private:
  static constexpr std::int64_t kNoBin = std::numeric_limits<std::int64_t>::min();

  struct Bin {
    std::int64_t index = kNoBin;
    double first_stamp_s = 0.0;
    Aggregate aggregate;
  };

  static std::size_t slot(std::int64_t index) {
    const std::int64_t bins = static_cast<std::int64_t>(kBins);
    return static_cast<std::size_t>(((index % bins) + bins) % bins);
  }

  void startBin(std::int64_t index, double stamp_s) {
    if (empty()) oldest_index_ = index;
    newest_index_ = index;
    Bin& bin = bins_[slot(index)];
    bin = Bin{index, stamp_s, Aggregate{}};
  }

  /// The closed bins still in the window: a slot belongs to it when it holds the bin of its index.
  void mergeClosedBins() {
    closed_ = Aggregate{};
    std::int64_t oldest = newest_index_;
    for (std::int64_t index = oldest_index_; index < newest_index_; ++index) {
      const Bin& bin = bins_[slot(index)];
      if (bin.index != index) continue;  // no sample fell in that bin
      closed_.merge(bin.aggregate);
      oldest = std::min(oldest, index);
    }
    oldest_index_ = oldest;
  }

  double bin_s_;
  std::array<Bin, kBins> bins_{};
  Aggregate closed_{};
  std::int64_t oldest_index_ = 0;
  std::int64_t newest_index_ = 0;
  double newest_stamp_s_ = 0.0;
  std::uint64_t samples_ = 0;
};

}  // namespace propulsion_estimator

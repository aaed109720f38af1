#pragma once

#include <limits>
#include <string>

#include "propulsion_estimator/common/config_error.h"

namespace propulsion_estimator {

/// A refused value of a configuration struct, named by its key path as the YAML file spells it
/// ("motor.kv_rpm_per_v", "segments[3].height_m"). validate() functions throw it without knowing
/// where the struct came from; a reader turns it into a located ConfigError with throwAtField.
class FieldError : public ConfigError {
 public:
  /// `field`: the key path ("motor.kv_rpm_per_v"); `problem`: what is wrong with its value.
  FieldError(const std::string& field, const std::string& problem)
      : ConfigError(field + ": " + problem), field_(field), problem_(problem) {}

  /// The key path of the refused value.
  const std::string& field() const { return field_; }
  /// What is wrong with it, without the key path.
  const std::string& problem() const { return problem_; }

 private:
  std::string field_;
  std::string problem_;
};

/// Range checks for validate() functions: throw FieldError(field, "<value> is outside <lo>..<hi><unit>")
/// unless lo <= value <= hi, and "<value> is outside 0..<hi><unit> (must be positive)" unless
/// 0 < value <= hi; without an upper bound "must be a positive number, got <value>" unless
/// 0 < value < infinity. NaN is outside every range. `unit` is appended as given (" m", " rpm/V").
void requireWithin(const std::string& field, double value, double lo, double hi, const std::string& unit = "");
/// Throws FieldError unless 0 < value <= hi (any finite positive value without `hi`); see requireWithin.
void requirePositive(const std::string& field, double value, double hi = std::numeric_limits<double>::infinity(),
                     const std::string& unit = "");

}  // namespace propulsion_estimator

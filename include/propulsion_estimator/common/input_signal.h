#pragma once

#include <array>
#include <optional>
#include <string>

/// @file
/// The scalar inputs, one entry each: everything the node's subscriptions and parameters, the
/// estimator's checks, the log readers, the diagnosis and the reports' "needs TOPIC" texts know of
/// a signal that arrives on a topic of its own as one number. A new one is a line in kScalarSpecs
/// (input_signal.cpp), the effect that reads it (its file and effects::Signal), and one field line
/// per log format (docs/contributing.md, "Adding a signal").
namespace propulsion_estimator {
namespace input {

/// The scalar inputs, in kScalarSpecs' order.
enum class Scalar { kStaticPressure, kAirTemperature, kRangefinder, kMotorTemperature };
constexpr int kScalarCount = 4;  ///< number of Scalar values
/// Every Scalar, in order.
constexpr std::array<Scalar, kScalarCount> kAllScalars = {Scalar::kStaticPressure, Scalar::kAirTemperature,
                                                          Scalar::kRangefinder, Scalar::kMotorTemperature};
/// One value per scalar input, indexed by index(Scalar).
template <typename T>
using PerScalar = std::array<T, kScalarCount>;
/// The position of `scalar` in a PerScalar.
constexpr int index(Scalar scalar) { return static_cast<int>(scalar); }
/// A PerScalar holding `value` for every scalar input.
template <typename T>
PerScalar<T> perScalar(const T& value) {
  PerScalar<T> all;
  all.fill(value);
  return all;
}

/// The ROS message a scalar arrives in, and the field it is read from.
enum class Message {
  kFluidPressure,  ///< sensor_msgs/FluidPressure.fluid_pressure, Pa
  kTemperature,    ///< sensor_msgs/Temperature.temperature, deg C
  kRange,          ///< sensor_msgs/Range.range, m, with the message's own min_range..max_range
};

/// One scalar input.
struct ScalarSpec {
  /// "air_temperature": the signal's name in logs' notes and the flight's signal list, and the
  /// stem of its parameters `<name>_topic` and `<name>/timeout_s`.
  const char* name;
  const char* description;  ///< "air temperature": for messages
  const char* unit;         ///< "deg C"
  /// A reading outside min..max is another unit (hPa, K) or a broken sensor, and is refused. A
  /// range's own bounds come with each message (sensor_msgs/Range); these are the widest allowed.
  double min;
  double max;  ///< see min
  double timeout_s;   ///< default staleness: a few periods of what MAVROS publishes
  const char* topic;  ///< default topic (MAVROS's where it has one)
  Message message;    ///< the message it arrives in
};

/// The entry of `scalar`.
const ScalarSpec& spec(Scalar scalar);
/// The scalar named `name` (ScalarSpec::name); nullopt for any other string.
std::optional<Scalar> scalarFromName(const std::string& name);
/// "air_temperature_topic": the parameter naming the topic of `scalar`.
std::string topicParameter(Scalar scalar);
/// "air_temperature/timeout_s": the parameter of its staleness timeout.
std::string timeoutParameter(Scalar scalar);
/// "sensor_msgs/Temperature": the message type `scalar` arrives in.
const char* messageType(Scalar scalar);
/// Every scalar's default timeout_s.
PerScalar<double> defaultTimeouts();
/// Every scalar's default topic.
PerScalar<std::string> defaultTopics();

}  // namespace input
}  // namespace propulsion_estimator

#include "propulsion_estimator/common/input_signal.h"

#include <limits>

namespace propulsion_estimator {
namespace input {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// In Scalar's order. Static pressure's range is the bench air's (ModelMetadata::validate); a
// barometer's die, which PX4 reports as the air's temperature, runs warmer than the air; no MAVROS
// topic carries a motor's temperature, so its topic is the package's own.
constexpr PerScalar<ScalarSpec> kScalarSpecs = {{
    {"static_pressure", "static pressure", "Pa", 30000.0, 110000.0, 1.0,
     "/mavros/imu/static_pressure", Message::kFluidPressure},
    {"air_temperature", "air temperature", "deg C", -60.0, 85.0, 5.0,
     "/mavros/imu/temperature_baro", Message::kTemperature},
    {"rangefinder", "rangefinder range", "m", 0.0, kInf, 0.5, "/mavros/rangefinder/rangefinder",
     Message::kRange},
    {"motor_temperature", "motor temperature", "deg C", -40.0, 200.0, 5.0,
     "/motor_temperature", Message::kTemperature},
}};

}  // namespace

const ScalarSpec& spec(Scalar scalar) { return kScalarSpecs[index(scalar)]; }

std::optional<Scalar> scalarFromName(const std::string& name) {
  for (Scalar scalar : kAllScalars) {
    if (name == spec(scalar).name) return scalar;
  }
  return std::nullopt;
}

std::string topicParameter(Scalar scalar) { return std::string(spec(scalar).name) + "_topic"; }

std::string timeoutParameter(Scalar scalar) { return std::string(spec(scalar).name) + "/timeout_s"; }

const char* messageType(Scalar scalar) {
  switch (spec(scalar).message) {
    case Message::kFluidPressure: return "sensor_msgs/FluidPressure";
    case Message::kTemperature: return "sensor_msgs/Temperature";
    case Message::kRange: return "sensor_msgs/Range";
  }
  return "?";
}

PerScalar<double> defaultTimeouts() {
  PerScalar<double> timeouts{};
  for (Scalar scalar : kAllScalars) timeouts[index(scalar)] = spec(scalar).timeout_s;
  return timeouts;
}

PerScalar<std::string> defaultTopics() {
  PerScalar<std::string> topics;
  for (Scalar scalar : kAllScalars) topics[index(scalar)] = spec(scalar).topic;
  return topics;
}

}  // namespace input
}  // namespace propulsion_estimator

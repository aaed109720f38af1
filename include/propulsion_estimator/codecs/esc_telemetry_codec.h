#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <topic_tools/shape_shifter.h>

#include "propulsion_estimator/onboard/esc_report.h"

namespace propulsion_estimator {

/// mavros_msgs/ESCTelemetry (ArduPilot's ESC_TELEMETRY_x_TO_y) and mavros_msgs/ESCStatus (PX4's
/// ESC_STATUS) without mavros_msgs, as RCOut (rcout_codec.h): received as a ShapeShifter, checked
/// against these names and md5sums (computed as ROS does, over the definitions with their nested
/// types, mavros 1.x and 2.x alike), decoded by hand; the simulator writes them the same way.
///@{
constexpr const char* kEscTelemetryDataType = "mavros_msgs/ESCTelemetry";
constexpr const char* kEscTelemetryMd5Sum = "7b1fb252ca6aa175fe8dd23d029b3362";  ///< of kEscTelemetryDataType
constexpr const char* kEscStatusDataType = "mavros_msgs/ESCStatus";
constexpr const char* kEscStatusMd5Sum = "145d49eaf5cfecbdfd50ae4a22fe82d4";  ///< of kEscStatusDataType
///@}
/// Full definitions as rosbag and rostopic expect them (the message, then std_msgs/Header, then
/// its item type).
///@{
const std::string& escTelemetryDefinition();
const std::string& escStatusDefinition();
///@}

/// Decoder of either message. decode() fills `out`, reusing its and its own buffer's storage.
/// Returns false with a one-line reason for another type (naming both it and its md5sum) or a
/// malformed payload (cut short, an item count larger than the bytes left, bytes after the items,
/// a negative rpm).
class EscTelemetryDecoder {
 public:
  /// Decodes `message` into `out`; false with a one-line reason in `error`.
  bool decode(const topic_tools::ShapeShifter& message, EscTelemetry* out, std::string* error);
  /// The serialized message alone, of `datatype` (either of the two), for a reader that has
  /// checked the type itself (a bag's connection).
  static bool decodePayload(const std::string& datatype, const std::uint8_t* data, std::uint32_t size,
                            EscTelemetry* out, std::string* error);

 private:
  std::vector<std::uint8_t> buffer_;
};

/// A ShapeShifter carrying `message` as mavros_msgs/ESCStatus (`px4`) or ESCTelemetry, for
/// publishing and bag writing; fields the type lacks are left out (ESCStatus has no temperature or
/// count).
topic_tools::ShapeShifter encodeEscTelemetry(const EscTelemetry& message, bool px4);

}  // namespace propulsion_estimator

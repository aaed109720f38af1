#pragma once

#include <ros/time.h>
#include <rosbag/bag.h>

#include <cstdint>
#include <string>

#include "propulsion_estimator/common/mavros_topics.h"
#include "propulsion_estimator/sim/flight/flight_sink.h"

namespace propulsion_estimator {

/// Simulated bags start at this time (2020-09-13T12:26:40Z), so that the same inputs and seed give
/// the same bag.
constexpr std::uint32_t kSimulatedBagStartSec = 1600000000;

/// The simulator's ground truth (propulsion_estimator/SimTruth); the flight's other topics are
/// MAVROS' (mavros_topics.h).
constexpr const char* kSimTruthTopic = "/sim/truth";

/// Writes a simulated flight into a bag: MAVROS topics with their message types
/// (/mavros/rc/out as mavros_msgs/RCOut through rcout_codec), the hottest motor's temperature as
/// sensor_msgs/Temperature, and the truth as propulsion_estimator/SimTruth. Message times are the
/// headers' stamps, kSimulatedBagStartSec + the sample's time. Frames: "map" (ENU world),
/// "base_link" (FLU body), "rangefinder", the motor's link.
class BagFlightSink : public sim::FlightSink {
 public:
  /// Opens `path` for writing (rosbag::BagException for an unwritable path).
  BagFlightSink(const std::string& path, rosbag::compression::CompressionType compression);
  ~BagFlightSink() override;

  /// Each writes one message on its topic (kRcOutTopic, ...), stamped kSimulatedBagStartSec plus
  /// the sample's time; rosbag::BagException when the bag cannot be written.
  ///@{
  void rcOut(const sim::RcOutSample& sample) override;
  void battery(const sim::BatterySample& sample) override;
  void imu(const sim::ImuSample& sample) override;
  void pose(const sim::PoseSample& sample) override;
  void velocity(const sim::VelocitySample& sample) override;
  void staticPressure(const sim::ScalarSample& sample) override;
  void airTemperature(const sim::ScalarSample& sample) override;
  void rangefinder(const sim::RangeSample& sample) override;
  void motorTemperature(const sim::ScalarSample& sample) override;
  void truth(const sim::TruthSample& sample) override;
  /// mavros_msgs/ESCStatus on kEscStatusTopic (PX4) or ESCTelemetry on kEscTelemetryTopic (ArduPilot).
  void escTelemetry(const sim::EscTelemetrySample& sample) override;
  ///@}

  /// Finishes the bag (rosbag::BagException when it cannot be written). The destructor closes it
  /// too, reporting a failure on stderr since it cannot throw.
  void close();

 private:
  static ros::Time stamp(double time_s);
  void writeTemperature(const char* topic, const sim::ScalarSample& sample);

  std::string path_;
  rosbag::Bag bag_;
  std::uint32_t rc_out_seq_ = 0;
};

}  // namespace propulsion_estimator

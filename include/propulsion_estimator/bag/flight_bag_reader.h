#pragma once

#include <rosbag/bag.h>

#include <memory>
#include <string>
#include <vector>

#include "propulsion_estimator/common/input_signal.h"
#include "propulsion_estimator/common/mavros_topics.h"
#include "propulsion_estimator/logs/flight_log_formats.h"
#include "propulsion_estimator/logs/flight_log_reader.h"

namespace propulsion_estimator {

/// The topic of each signal of a flight bag; MAVROS' names (those the simulator writes) by default.
/// rc_out and battery are required, the others optional.
struct FlightBagTopics {
  std::string rc_out = kRcOutTopic;                     ///< mavros_msgs/RCOut
  std::string battery = kBatteryTopic;                  ///< sensor_msgs/BatteryState
  std::string imu = kImuTopic;                          ///< sensor_msgs/Imu
  std::string pose = kPoseTopic;                        ///< geometry_msgs/PoseStamped
  std::string velocity = kVelocityTopic;                ///< geometry_msgs/TwistStamped
  /// Each scalar input's topic (its ScalarSpec's message type), by input::index.
  input::PerScalar<std::string> inputs = input::defaultTopics();
  std::string esc_telemetry = kEscTelemetryTopic;       ///< mavros_msgs/ESCTelemetry (ArduPilot)
  std::string esc_status = kEscStatusTopic;             ///< mavros_msgs/ESCStatus (PX4)

  /// The signals' names, as above: flightSignalNames().
  static const std::vector<std::string>& names();
  /// The topic of the signal `name`, or nullptr when there is no such signal.
  std::string* find(const std::string& name);
};

/// A flight bag opened for reading, on the manifest's clock: seconds from the bag's first message
/// on any topic (taken from the bag's index, as `rosbag info` and rosbag.Bag.get_start_time()
/// count). Message times are the bag's record times. Only the requested topics' messages are ever
/// read: the simulator's /sim/truth is not one of them, and its type matches none of the signals.
/// Readers may work on different threads: their bags are made, opened and destroyed under one
/// lock, since rosbag loads and unloads a plugin then; no other rosbag::Bag may come or go meanwhile.
class FlightBagReader : public FlightLogReader {
 public:
  /// Opens `path`. InputError as requireRegularFile (no such file, a folder, a device); DataError "<path>: not a readable bag: <why>"
  /// (a bag damaged past its header, cut short say, or never closed: "...; `rosbag reindex` ..."),
  /// "<path>: no messages".
  explicit FlightBagReader(const std::string& path);
  ~FlightBagReader() override;
  FlightBagReader(const FlightBagReader&) = delete;
  FlightBagReader& operator=(const FlightBagReader&) = delete;

  /// The bag's path, as given.
  const std::string& path() const override { return path_; }
  /// From the first message to the last, in seconds.
  double durationS() const override { return duration_s_; }

  /// read(topics, motors) with the options' sources as topics (ConfigError for bad options).
  FlightStreams read(const FlightLogOptions& options) const override;

  /// Reads the signals in one pass over their topics, in time order. Motors 1..`motors` are RCOut
  /// channels 1..`motors`. Values are as logged (the battery current keeps the autopilot's sign),
  /// except that IMU messages without orientation (covariance -1, REP-145) and rangefinder readings
  /// outside the sensor's min_range..max_range are left out. An optional topic that the bag lacks
  /// leaves its stream empty. DataError "<path>: <topic>: <problem>" for a required topic
  /// without messages, a topic of another type or md5sum than expected, an RCOut message with
  /// fewer channels than `motors`, or a malformed message; "<path>: reading failed after <t> s:
  /// <why>" when not even the first message can be read. A bag whose chunk at t s cannot be read
  /// (corrupt compressed data) gives the messages before it, and that line as refusal().
  FlightStreams read(const FlightBagTopics& topics, int motors) const;
  /// "" until read() met a chunk it could not read; then the line saying where.
  std::string refusal() const override { return refusal_; }
  /// True: its signals are the topics FlightLogOptions::sources names.
  bool readsNamedSources() const override { return true; }

 private:
  std::string path_;
  mutable std::string refusal_;  // set by read(): the reader's interface reads it after read()
  std::unique_ptr<rosbag::Bag> bag_;
  ros::Time start_;
  double duration_s_ = 0.0;
};

/// The rosbag format for the FlightLogFormats registry: files that start with "#ROSBAG V2.0",
/// opened as FlightBagReader.
FlightLogFormat flightBagFormat();

}  // namespace propulsion_estimator

#include "propulsion_estimator/bag/flight_bag_reader.h"

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <ros/serialization.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/Range.h>
#include <sensor_msgs/Temperature.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "propulsion_estimator/bag/bag_records.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/codecs/esc_telemetry_codec.h"
#include "propulsion_estimator/codecs/rcout_codec.h"

namespace propulsion_estimator {
namespace {

enum class Signal {
  kRcOut,
  kBattery,
  kImu,
  kPose,
  kVelocity,
  kInput,  // a scalar input: Source::scalar says which
  kEscTelemetry,
  kEscStatus
};

// A signal to read: where, of which type, and whether the flight is refused without it.
struct Source {
  Signal signal;
  const std::string* topic;
  std::string datatype;
  std::string md5sum;
  bool required;
  input::Scalar scalar = input::Scalar::kStaticPressure;  // for Signal::kInput
};

template <typename Message>
Source sourceOf(Signal signal, const std::string& topic, bool required = false) {
  return {signal, &topic, ros::message_traits::DataType<Message>::value(),
          ros::message_traits::MD5Sum<Message>::value(), required};
}

Source inputSource(input::Scalar scalar, const std::string& topic) {
  Source source;
  switch (input::spec(scalar).message) {
    case input::Message::kFluidPressure: source = sourceOf<sensor_msgs::FluidPressure>(Signal::kInput, topic); break;
    case input::Message::kTemperature: source = sourceOf<sensor_msgs::Temperature>(Signal::kInput, topic); break;
    case input::Message::kRange: source = sourceOf<sensor_msgs::Range>(Signal::kInput, topic); break;
  }
  source.scalar = scalar;
  return source;
}

std::vector<Source> sourcesOf(const FlightBagTopics& topics) {
  std::vector<Source> sources = {{Signal::kRcOut, &topics.rc_out, kRcOutDataType, kRcOutMd5Sum, true},
                                 sourceOf<sensor_msgs::BatteryState>(Signal::kBattery, topics.battery, true),
                                 sourceOf<sensor_msgs::Imu>(Signal::kImu, topics.imu),
                                 sourceOf<geometry_msgs::PoseStamped>(Signal::kPose, topics.pose),
                                 sourceOf<geometry_msgs::TwistStamped>(Signal::kVelocity, topics.velocity)};
  for (input::Scalar scalar : input::kAllScalars) {
    sources.push_back(inputSource(scalar, topics.inputs[input::index(scalar)]));
  }
  sources.push_back({Signal::kEscTelemetry, &topics.esc_telemetry, kEscTelemetryDataType, kEscTelemetryMd5Sum, false});
  sources.push_back({Signal::kEscStatus, &topics.esc_status, kEscStatusDataType, kEscStatusMd5Sum, false});
  return sources;
}

// Whether a serialized sensor_msgs/BatteryState's float32[] arrays (cell_voltage,
// cell_temperature) hold no more elements than the record's bytes: roscpp's deserializer resizes an
// array to its declared length before it reads a byte of it, so a damaged length of a few billion
// would allocate gigabytes. "" when they fit or the record ends before them (the deserializer then
// refuses it); else the one line naming the field, the count and the bytes left.
std::string batteryArraysProblem(const std::uint8_t* data, std::uint32_t size) {
  std::uint64_t at = 0;
  const auto next = [&](std::uint64_t bytes) { return (at += bytes) <= size; };
  const auto count = [&](std::uint32_t* value) {
    if (at + 4 > size) return false;
    std::memcpy(value, data + at, 4);
    at += 4;
    return true;
  };
  std::uint32_t frame_id_bytes = 0;
  // Header: seq, stamp (two uint32), frame_id; then seven float32 and four uint8 or bool.
  if (!next(12) || !count(&frame_id_bytes) || !next(frame_id_bytes) || !next(7 * 4 + 4)) return "";
  for (const char* field : {"cell_voltage", "cell_temperature"}) {
    std::uint32_t elements = 0;
    if (!count(&elements)) return "";
    const std::uint64_t left = size - at;
    if (std::uint64_t{elements} * 4 > left) {
      return std::string("malformed sensor_msgs/BatteryState: ") + field + " declares " + std::to_string(elements) +
             " elements, the " + std::to_string(left) + " bytes left hold " + std::to_string(left / 4);
    }
    next(std::uint64_t{elements} * 4);
  }
  return "";
}

// The messages of one pass, decoded into storage reused from message to message: the streams'
// vectors grow, nothing else is allocated per message (a frame_id longer than the small-string
// buffer aside).
class StreamBuilder {
 public:
  StreamBuilder(FlightStreams* streams, int motors) : streams_(streams), motors_(motors) {}

  // Decodes one message of `signal`; false with the reason in `error` for a malformed one or an
  // RCOut message with too few channels.
  bool add(const Source& source, double time_s, std::uint8_t* data, std::uint32_t size, std::string* error) {
    ros::serialization::IStream stream(data, size);
    switch (source.signal) {
      case Signal::kRcOut:
        return addRcOut(time_s, data, size, error);
      case Signal::kBattery:
        *error = batteryArraysProblem(data, size);
        if (!error->empty()) return false;
        ros::serialization::deserialize(stream, battery_);
        streams_->battery.push_back({time_s, battery_.voltage, battery_.current});
        return true;
      case Signal::kImu:
        ros::serialization::deserialize(stream, imu_);
        // REP-145: covariance -1 says the message carries no orientation.
        if (imu_.orientation_covariance[0] == -1.0) return true;
        streams_->imu.push_back({time_s,
                                 Eigen::Quaterniond(imu_.orientation.w, imu_.orientation.x, imu_.orientation.y,
                                                    imu_.orientation.z),
                                 Eigen::Vector3d(imu_.linear_acceleration.x, imu_.linear_acceleration.y,
                                                 imu_.linear_acceleration.z)});
        return true;
      case Signal::kPose:
        ros::serialization::deserialize(stream, pose_);
        streams_->altitude_m.push_back({time_s, pose_.pose.position.z});
        return true;
      case Signal::kVelocity:
        ros::serialization::deserialize(stream, velocity_);
        streams_->vertical_speed_m_s.push_back({time_s, velocity_.twist.linear.z});
        streams_->horizontal_velocity.push_back({time_s, velocity_.twist.linear.x, velocity_.twist.linear.y});
        return true;
      case Signal::kInput:
        addInput(source.scalar, time_s, stream);
        return true;
      case Signal::kEscTelemetry:
      case Signal::kEscStatus:
        return addEsc(source.signal == Signal::kEscStatus, time_s, data, size, error);
    }
    return true;
  }

 private:
  void addInput(input::Scalar scalar, double time_s, ros::serialization::IStream& stream) {
    std::vector<ScalarReading>& readings = streams_->input(scalar);
    switch (input::spec(scalar).message) {
      case input::Message::kFluidPressure:
        ros::serialization::deserialize(stream, pressure_);
        readings.push_back({time_s, pressure_.fluid_pressure});
        return;
      case input::Message::kTemperature:
        ros::serialization::deserialize(stream, temperature_);
        readings.push_back({time_s, temperature_.temperature});
        return;
      case input::Message::kRange:
        ros::serialization::deserialize(stream, range_);
        // REP-117: -inf and +inf say below and beyond the sensor's reach; NaN fails both tests.
        if (range_.range >= range_.min_range && range_.range <= range_.max_range) {
          readings.push_back({time_s, range_.range});
        }
        return;
    }
  }

  bool addRcOut(double time_s, const std::uint8_t* data, std::uint32_t size, std::string* error) {
    if (!RcOutDecoder::decodePayload(data, size, &rc_out_, error)) return false;
    if (static_cast<int>(rc_out_.channels.size()) < motors_) {
      *error = std::to_string(rc_out_.channels.size()) + " channels, fewer than the " + std::to_string(motors_) +
               " motors";
      return false;
    }
    RcOutFrame& frame = streams_->rc_out.emplace_back();
    frame.time_s = time_s;
    for (int k = 0; k < motors_; ++k) frame.pwm_us[k] = rc_out_.channels[k];
    return true;
  }

  bool addEsc(bool status, double time_s, const std::uint8_t* data, std::uint32_t size, std::string* error) {
    if (!EscTelemetryDecoder::decodePayload(status ? kEscStatusDataType : kEscTelemetryDataType, data, size, &esc_,
                                            error)) {
      return false;
    }
    EscTelemetryReading& reading = streams_->esc.emplace_back();
    reading.time_s = time_s;
    reading.status = status;
    reading.escs = std::min<int>(static_cast<int>(esc_.escs.size()), kMaxMotors);
    for (int k = 0; k < reading.escs; ++k) {
      const EscReport& report = esc_.escs[k];
      reading.rpm[k] = report.rpm;
      reading.current_a[k] = report.current_a;
      reading.voltage_v[k] = report.voltage_v;
      reading.count[k] = report.count;
    }
    return true;
  }

  FlightStreams* streams_;
  int motors_;
  RcOutMessage rc_out_;
  sensor_msgs::BatteryState battery_;
  sensor_msgs::Imu imu_;
  geometry_msgs::PoseStamped pose_;
  geometry_msgs::TwistStamped velocity_;
  sensor_msgs::FluidPressure pressure_;
  sensor_msgs::Temperature temperature_;
  sensor_msgs::Range range_;
  EscTelemetry esc_;
};

// Capacity for every message of `topic`, from the bag's index.
template <typename Reading>
void reserveFor(const rosbag::Bag& bag, const std::string& topic, std::vector<Reading>* stream) {
  stream->reserve(stream->size() + rosbag::View(bag, rosbag::TopicQuery(topic)).size());
}

void reserve(const rosbag::Bag& bag, const Source& source, FlightStreams* streams) {
  const std::string& topic = *source.topic;
  switch (source.signal) {
    case Signal::kRcOut: return reserveFor(bag, topic, &streams->rc_out);
    case Signal::kBattery: return reserveFor(bag, topic, &streams->battery);
    case Signal::kImu: return reserveFor(bag, topic, &streams->imu);
    case Signal::kPose: return reserveFor(bag, topic, &streams->altitude_m);
    case Signal::kVelocity:
      reserveFor(bag, topic, &streams->horizontal_velocity);
      return reserveFor(bag, topic, &streams->vertical_speed_m_s);
    case Signal::kInput: return reserveFor(bag, topic, &streams->input(source.scalar));
    case Signal::kEscTelemetry:
    case Signal::kEscStatus: return reserveFor(bag, topic, &streams->esc);
  }
}

// rosbag::Bag loads its encryption plugin through class_loader when it is made and opened, and
// unloads it when destroyed; class_loader does not guard loading against unloading on another
// thread (two bags opened at once fail with "Could not create object of class type
// rosbag::NoEncryptor"). Bags are made, opened and destroyed under this lock; reading needs none.
std::mutex& bagLifetimeMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

const std::vector<std::string>& FlightBagTopics::names() { return flightSignalNames(); }

std::string* FlightBagTopics::find(const std::string& name) {
  // In names()' order: the fixed signals, each scalar input's, the ESCs'.
  std::vector<std::string*> topics = {&rc_out, &battery, &imu, &pose, &velocity};
  for (std::string& topic : inputs) topics.push_back(&topic);
  topics.insert(topics.end(), {&esc_telemetry, &esc_status});
  for (std::size_t i = 0; i < names().size(); ++i) {
    if (names()[i] == name) return topics[i];
  }
  return nullptr;
}

namespace {

// Seconds from `start` to `time`, from their nanoseconds: ros::Duration throws std::runtime_error
// for a span beyond 2^31 s, which a corrupt stamp gives (found by fuzz_flight_bag).
double secondsSince(const ros::Time& start, const ros::Time& time) {
  return static_cast<double>(static_cast<std::int64_t>(time.toNSec() - start.toNSec())) * 1e-9;
}

}  // namespace

FlightBagReader::FlightBagReader(const std::string& path) : path_(path) {
  requireRegularFile(path);
  // The record walk opens no rosbag object: outside the lock, readers run it in parallel.
  const BagRecordCheck checked = checkBagRecords(path);
  if (!checked.damage.empty()) {
    // A bag cut short (a full card, lost power) or damaged past its header is read through its
    // index, which `rosbag reindex` rebuilds from the records that are whole.
    throw DataError(path + ": not a readable bag: " + checked.damage +
                    (checked.past_bag_header ? "; `rosbag reindex` rebuilds its index from the whole records" : ""));
  }
  // Declared after the lock, a bag refused here is destroyed before the lock is released.
  const std::lock_guard<std::mutex> lock(bagLifetimeMutex());
  auto bag = std::make_unique<rosbag::Bag>();
  try {
    bag->open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException& e) {
    throw DataError(path + ": not a readable bag: " + e.what() +
                    " (a recording never closed); `rosbag reindex` indexes it");
  } catch (const rosbag::BagException& e) {
    throw DataError(path + ": not a readable bag: " + e.what());
  }
  rosbag::View all(*bag);
  if (all.size() == 0) throw DataError(path + ": no messages");
  start_ = all.getBeginTime();
  duration_s_ = secondsSince(start_, all.getEndTime());
  bag_ = std::move(bag);
}

FlightBagReader::~FlightBagReader() {
  const std::lock_guard<std::mutex> lock(bagLifetimeMutex());
  bag_.reset();
}

FlightStreams FlightBagReader::read(const FlightLogOptions& options) const {
  FlightBagTopics topics;
  for (const auto& [name, topic] : options.sources) {
    std::string* slot = topics.find(name);
    if (slot == nullptr) options.validate(path_);  // throws, naming the signal
    *slot = topic;
  }
  return read(topics, options.motors);
}

FlightStreams FlightBagReader::read(const FlightBagTopics& topics, int motors) const {
  if (motors < 1 || motors > kMaxMotors) {
    throw ConfigError(path_ + ": " + std::to_string(motors) + " motors, expected 1.." + std::to_string(kMaxMotors));
  }
  FlightStreams streams;
  streams.source = path_;
  streams.motors = motors;
  const std::vector<Source> sources = sourcesOf(topics);
  std::vector<std::string> requested;
  for (const Source& source : sources) {
    rosbag::View view(*bag_, rosbag::TopicQuery(*source.topic));
    if (view.size() == 0) {
      if (source.required) throw DataError(path_ + ": " + *source.topic + ": no messages (a required topic)");
      continue;
    }
    for (const rosbag::ConnectionInfo* connection : view.getConnections()) {
      if (connection->datatype != source.datatype || connection->md5sum != source.md5sum) {
        throw DataError(path_ + ": " + *source.topic + ": expected " + source.datatype + " (md5sum " + source.md5sum +
                        "), got " + connection->datatype + " (md5sum " + connection->md5sum + ")");
      }
    }
    reserve(*bag_, source, &streams);
    requested.push_back(*source.topic);
  }

  StreamBuilder builder(&streams, motors);
  std::vector<std::uint8_t> buffer;
  std::string error;
  double time_s = 0.0;
  bool any = false;
  refusal_.clear();
  try {
    for (const rosbag::MessageInstance& message : rosbag::View(*bag_, rosbag::TopicQuery(requested))) {
      time_s = secondsSince(start_, message.getTime());
      // The time comes from the index; the chunk is read (and a corrupt one found) below.
      const std::uint32_t size = message.size();
      if (buffer.size() < size) buffer.resize(size);
      ros::serialization::OStream out(buffer.data(), size);
      message.write(out);
      any = true;
      // Two signals may share a topic (both temperatures on one, say): each gets the message.
      for (const Source& source : sources) {
        if (*source.topic != message.getTopic()) continue;
        bool added = false;
        try {
          added = builder.add(source, time_s, buffer.data(), size, &error);
        } catch (const ros::serialization::StreamOverrunException& e) {
          error = "malformed " + source.datatype + ": " + e.what();
        }
        if (!added) {
          throw DataError(path_ + ": " + message.getTopic() + ": at " + formatPrintf("%.3f", time_s) + " s: " + error);
        }
      }
    }
  } catch (const rosbag::BagException& e) {
    // A chunk that cannot be read (its compressed data corrupt) ends the flight there, as a damaged
    // ULog's first bad message does: what came before it is kept.
    const std::string line = path_ + ": reading failed after " + formatPrintf("%.3f", time_s) + " s: " + e.what();
    if (!any) throw DataError(line);
    refusal_ = line;
  }
  return streams;
}

FlightLogFormat flightBagFormat() {
  return {"rosbag", "#ROSBAG V2.0",
          [](const std::string& path) -> std::unique_ptr<FlightLogReader> {
            return std::make_unique<FlightBagReader>(path);
          }};
}

}  // namespace propulsion_estimator

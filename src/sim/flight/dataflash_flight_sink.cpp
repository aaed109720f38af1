#include "propulsion_estimator/sim/flight/dataflash_flight_sink.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/logs/autopilot_frames.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// Type ids of the messages written.
enum Id : std::uint8_t { kRcou = 1, kBat, kImu, kAtt, kXkf1, kBaro, kRfnd, kEsc };
constexpr int kRcouChannels = 14;

// RFND Stat (RangeFinder::Status).
enum RangeStatus : std::uint8_t { kOutOfRangeLow = 2, kOutOfRangeHigh = 3, kGood = 4 };

}  // namespace

DataflashFlightSink::DataflashFlightSink(double boot_s) : boot_s_(boot_s) {
  std::string format = "Q", labels = "TimeUS";
  for (int k = 1; k <= kRcouChannels; ++k) {
    format += 'H';
    labels += ",C" + std::to_string(k);
  }
  writer_.define(kRcou, "RCOU", format, labels);
  writer_.define(kBat, "BAT", "QBffff", "TimeUS,Inst,Volt,VoltR,Curr,CurrTot");
  writer_.define(kImu, "IMU", "QBffffff", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ");
  writer_.define(kAtt, "ATT", "Qffffff", "TimeUS,DesRoll,Roll,DesPitch,Pitch,DesYaw,Yaw");
  writer_.define(kXkf1, "XKF1", "QBfffffff", "TimeUS,C,VN,VE,VD,dPD,PN,PE,PD");
  writer_.define(kBaro, "BARO", "QBffff", "TimeUS,I,Alt,Press,Temp,CRt");
  writer_.define(kRfnd, "RFND", "QBfBB", "TimeUS,Instance,Dist,Stat,Orient");
  writer_.define(kEsc, "ESC", "QBfffhff", "TimeUS,Instance,RPM,Volt,Curr,Temp,CTot,MotTemp");
}

BinaryPayload DataflashFlightSink::start(double time_s) const {
  return BinaryPayload().put(static_cast<std::uint64_t>(std::llround((boot_s_ + time_s) * 1e6)));
}

void DataflashFlightSink::rcOut(const RcOutSample& sample) {
  BinaryPayload payload = start(sample.time_s);
  for (int k = 0; k < kRcouChannels; ++k) {
    payload.put<std::uint16_t>(k < static_cast<int>(sample.channels.size()) ? sample.channels[k] : 0);
  }
  writer_.write(kRcou, payload);
}

void DataflashFlightSink::battery(const BatterySample& sample) {
  const auto volts = static_cast<float>(sample.voltage_v);
  writer_.write(kBat, start(sample.time_s).put<std::uint8_t>(0).put(volts).put(volts)
                          .put(static_cast<float>(sample.current_a)).put(0.0f));
}

void DataflashFlightSink::imu(const ImuSample& sample) {
  const Eigen::Vector3d& w = sample.angular_velocity_rad_s;
  const Eigen::Vector3d& f = sample.linear_acceleration_m_s2;
  writer_.write(kImu, start(sample.time_s).put<std::uint8_t>(0).put(static_cast<float>(w.x()))
                          .put(static_cast<float>(-w.y())).put(static_cast<float>(-w.z()))
                          .put(static_cast<float>(f.x())).put(static_cast<float>(-f.y())).put(static_cast<float>(-f.z())));
  // Body FLU to ENU as FRD to NED, then as ZYX Euler angles in degrees.
  const Eigen::Matrix3d r = swapNedEnuFrdFlu(sample.orientation).toRotationMatrix();
  const double roll = std::atan2(r(2, 1), r(2, 2));
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  const auto degrees = [](double rad) { return static_cast<float>(rad * 180.0 / M_PI); };
  writer_.write(kAtt, start(sample.time_s).put(0.0f).put(degrees(roll)).put(0.0f).put(degrees(pitch)).put(0.0f)
                          .put(degrees(yaw)));
}

void DataflashFlightSink::pose(const PoseSample& sample) { altitude_m_ = sample.position_m.z(); }

void DataflashFlightSink::velocity(const VelocitySample& sample) {
  const Eigen::Vector3d& v = sample.linear_m_s;
  writer_.write(kXkf1, start(sample.time_s).put<std::uint8_t>(0).put(static_cast<float>(v.y()))
                           .put(static_cast<float>(v.x())).put(static_cast<float>(-v.z())).put(0.0f).put(0.0f)
                           .put(0.0f).put(static_cast<float>(-altitude_m_)));
}

void DataflashFlightSink::staticPressure(const ScalarSample& sample) {
  writer_.write(kBaro, start(sample.time_s).put<std::uint8_t>(0).put(0.0f).put(static_cast<float>(sample.value))
                           .put(static_cast<float>(air_temperature_c_)).put(0.0f));
}

void DataflashFlightSink::airTemperature(const ScalarSample& sample) { air_temperature_c_ = sample.value; }

void DataflashFlightSink::rangefinder(const RangeSample& sample) {
  const double range = sample.range_m;
  const std::uint8_t status = range < sample.min_range_m   ? kOutOfRangeLow
                              : range > sample.max_range_m ? kOutOfRangeHigh
                                                           : kGood;
  const double logged = std::clamp(range, sample.min_range_m, sample.max_range_m);
  writer_.write(kRfnd, start(sample.time_s).put<std::uint8_t>(0).put(static_cast<float>(logged)).put(status)
                           .put<std::uint8_t>(25));
}

// A motor temperature alone is an ESC row of instance 0 without telemetry (RPM, Volt, Curr NaN).
void DataflashFlightSink::motorTemperature(const ScalarSample& sample) {
  const auto hottest = static_cast<float>(sample.value);
  writer_.write(kEsc, start(sample.time_s).put<std::uint8_t>(0).put(NAN).put(NAN).put(NAN)
                          .put(static_cast<std::int16_t>(std::lround(hottest - 5.0f))).put(0.0f).put(hottest));
}

// ArduPilot logs one ESC row per ESC (AP_ESC_Telem::write_log_messages); the motor temperature has
// its own rows above, so MotTemp is NaN here.
void DataflashFlightSink::escTelemetry(const EscTelemetrySample& sample) {
  for (std::size_t k = 0; k < sample.escs.size(); ++k) {
    const EscReading& esc = sample.escs[k];
    writer_.write(kEsc, start(sample.time_s).put(static_cast<std::uint8_t>(k)).put(static_cast<float>(esc.rpm))
                            .put(static_cast<float>(esc.voltage_v)).put(static_cast<float>(esc.current_a))
                            .put(static_cast<std::int16_t>(std::lround(esc.temperature_c))).put(0.0f).put(NAN));
  }
}

}  // namespace sim
}  // namespace propulsion_estimator

// The ROS layer of the simulator, without a master: a short simulated flight written to a bag and
// read back with rosbag::View, and the `simulate` command end to end.
#include <gtest/gtest.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <rosbag/view.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/Range.h>
#include <sensor_msgs/Temperature.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "propulsion_estimator/SimTruth.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "propulsion_estimator/bag/bag_flight_sink.h"
#include "propulsion_estimator/codecs/esc_telemetry_codec.h"
#include "propulsion_estimator/codecs/rcout_codec.h"
#include "simulate_command.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace fs = std::filesystem;

namespace {

// Take off to 1 m, hover, land: 20 s at rc/out 25 Hz.
std::string shortProfile() {
  return "autopilot: {flavour: px4, pwm_min_us: 1100, pwm_max_us: 1950, disarmed_pwm_us: 900, rc_out_rate_hz: 25}\n"
         "vehicle:\n  urdf: " +
         repoPath("config/f450_quad.urdf") +
         "\n  centre_of_mass_offset_m: [0, 0, 0]\n  landing_gear: {height_m: 0.12, half_width_m: 0.12}\n"
         "  drag_area_m2: 0.04\n  battery_initial_soc: 0.9\n"
         "payload_cable: {length_m: 1.0, attach_point_m: [0, 0, -0.04], stiffness_n_per_m: 1000, damping_n_s_per_m: "
         "10}\n"
         "manifest: {settle_s: 3}\n"
         "segments:\n  - {type: wait, duration_s: 1}\n  - {type: takeoff, height_m: 1.0, rate_m_s: 1.0}\n"
         "  - {type: hover, duration_s: 8}\n  - {type: land, rate_m_s: 1.0}\n";
}

class TempDir {
 public:
  TempDir()
      : path_(fs::temp_directory_path() / ("pe_sim_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

int runCommand(std::vector<std::string> args) {
  args.insert(args.begin(), "simulate");
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  return pe::runSimulateCommand(static_cast<int>(argv.size()), argv.data());
}

void writeFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace

TEST(BagFlightSink, WritesMavrosTopicsWithTheirTypesAndRates) {
  TempDir dir;
  const pe::sim::FlightProfile profile = pe::sim::parseFlightProfileYaml(shortProfile(), dir.file("profile.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  pe::sim::FlightResult result;
  {
    pe::BagFlightSink sink(dir.file("flight.bag"), rosbag::compression::Uncompressed);
    result = pe::sim::simulateFlight(pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")), {},
                                     profile, vehicle, 1, &sink);
  }
  rosbag::Bag bag(dir.file("flight.bag"), rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::map<std::string, std::pair<std::string, std::string>> types;  // topic -> (type, md5)
  std::map<std::string, std::size_t> counts;
  for (const rosbag::ConnectionInfo* connection : view.getConnections()) {
    types[connection->topic] = {connection->datatype, connection->md5sum};
  }
  const std::map<std::string, std::string> expected_types = {
      {"/mavros/rc/out", "mavros_msgs/RCOut"},
      {"/mavros/battery", "sensor_msgs/BatteryState"},
      {"/mavros/imu/data", "sensor_msgs/Imu"},
      {"/mavros/local_position/pose", "geometry_msgs/PoseStamped"},
      {"/mavros/local_position/velocity_local", "geometry_msgs/TwistStamped"},
      {"/mavros/imu/static_pressure", "sensor_msgs/FluidPressure"},
      {"/mavros/imu/temperature_baro", "sensor_msgs/Temperature"},
      {"/mavros/rangefinder/rangefinder", "sensor_msgs/Range"},
      {"/motor_temperature", "sensor_msgs/Temperature"},
      {"/mavros/esc_status", "mavros_msgs/ESCStatus"},
      {"/sim/truth", "propulsion_estimator/SimTruth"}};
  ASSERT_EQ(types.size(), expected_types.size());
  for (const auto& [topic, type] : expected_types) EXPECT_EQ(types[topic].first, type) << topic;
  EXPECT_EQ(types["/mavros/rc/out"].second, "52cacf104bab5ae3b103cfe176590713");
  EXPECT_EQ(types["/mavros/esc_status"].second, "145d49eaf5cfecbdfd50ae4a22fe82d4");

  pe::RcOutDecoder decoder;
  pe::RcOutMessage rc_out;
  std::string error;
  double hover_pwm = 0.0;
  int hover_samples = 0;
  for (const rosbag::MessageInstance& message : view) {
    ++counts[message.getTopic()];
    if (message.getTopic() == "/mavros/esc_status") {
      pe::EscTelemetryDecoder esc_decoder;
      pe::EscTelemetry esc;
      ASSERT_TRUE(esc_decoder.decode(*message.instantiate<topic_tools::ShapeShifter>(), &esc, &error)) << error;
      ASSERT_EQ(esc.escs.size(), 4u);
      EXPECT_EQ(esc.stamp_s, message.getTime().toSec());
    }
    const double t = (message.getTime() - ros::Time(pe::kSimulatedBagStartSec)).toSec();
    if (message.getTopic() == "/mavros/rc/out") {
      ASSERT_TRUE(decoder.decode(*message.instantiate<topic_tools::ShapeShifter>(), &rc_out, &error)) << error;
      ASSERT_EQ(rc_out.channels.size(), 8u);
      ASSERT_EQ(rc_out.header.stamp, message.getTime());
      if (t == 0.0) {
        EXPECT_EQ(rc_out.channels, (std::vector<std::uint16_t>{900, 900, 900, 900, 0, 0, 0, 0}));
      }
      if (t >= result.segments[0].start_s && t <= result.segments[0].end_s) {
        for (int k = 0; k < 4; ++k) hover_pwm += rc_out.channels[k];
        hover_samples += 4;
      }
    }
    if (message.getTopic() == "/mavros/battery") {
      const sensor_msgs::BatteryState::ConstPtr battery = message.instantiate<sensor_msgs::BatteryState>();
      if (t >= result.segments[0].start_s && t <= result.segments[0].end_s) {
        EXPECT_LT(battery->current, -10.0f);  // PX4 through MAVROS
      }
      // Unmeasured fields are NaN, as the message definition asks.
      EXPECT_TRUE(std::isnan(battery->temperature));
      EXPECT_TRUE(std::isnan(battery->charge));
      EXPECT_TRUE(std::isnan(battery->capacity));
      EXPECT_TRUE(std::isnan(battery->design_capacity));
      EXPECT_GT(battery->voltage, 11.0f);
      EXPECT_GE(battery->percentage, 0.0f);
      EXPECT_LE(battery->percentage, 1.0f);
      EXPECT_TRUE(battery->cell_voltage.empty());
    }
    if (message.getTopic() == "/sim/truth") {
      const pe::SimTruth::ConstPtr truth = message.instantiate<pe::SimTruth>();
      ASSERT_EQ(truth->motors.size(), 4u);
      ASSERT_EQ(truth->ground_effect_factor.size(), 4u);
      EXPECT_DOUBLE_EQ(truth->total_mass_kg, 1.315);
    }
  }
  EXPECT_GT(hover_pwm / hover_samples, 1600.0);
  EXPECT_LT(hover_pwm / hover_samples, 1750.0);
  EXPECT_EQ(view.getBeginTime(), ros::Time(pe::kSimulatedBagStartSec));

  const double duration = result.duration_s;
  const auto expected = [&](double rate_hz) {
    return static_cast<std::size_t>(std::floor(duration * rate_hz + 1e-6)) + 1;
  };
  const pe::sim::FlightSensorParams sensors;
  EXPECT_EQ(counts["/mavros/rc/out"], expected(25.0));
  EXPECT_EQ(counts["/sim/truth"], expected(25.0));
  EXPECT_EQ(counts["/mavros/battery"], expected(sensors.battery_rate_hz));
  EXPECT_EQ(counts["/mavros/imu/data"], expected(sensors.imu_rate_hz));
  EXPECT_EQ(counts["/mavros/local_position/pose"], expected(sensors.pose_rate_hz));
  EXPECT_EQ(counts["/mavros/local_position/velocity_local"], expected(sensors.pose_rate_hz));
  EXPECT_EQ(counts["/mavros/imu/static_pressure"], expected(sensors.pressure_rate_hz));
  EXPECT_EQ(counts["/mavros/imu/temperature_baro"], expected(sensors.air_temperature_rate_hz));
  EXPECT_EQ(counts["/mavros/rangefinder/rangefinder"], expected(sensors.rangefinder_rate_hz));
  EXPECT_EQ(counts["/mavros/esc_status"], expected(sensors.esc_telemetry_rate_hz));
  EXPECT_EQ(counts["/motor_temperature"], expected(sensors.motor_temperature_rate_hz));
}

TEST(BagFlightSink, CarriesEverySignalTheGapDiagnosisReads) {
  // Each reading against the truth of the same flight at the nearest /sim/truth stamp (25 Hz):
  // barometer and its temperature (air density), rangefinder (height, ground effect), motor
  // temperature, local position and velocity (vertical speed), battery voltage and PX4's negated
  // current (the current view of the thrust), IMU (attitude, acceleration).
  TempDir dir;
  const pe::sim::FlightProfile profile = pe::sim::parseFlightProfileYaml(shortProfile(), dir.file("profile.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  const pe::sim::SimParams params = pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
  {
    pe::BagFlightSink sink(dir.file("flight.bag"), rosbag::compression::Uncompressed);
    pe::sim::simulateFlight(params, {}, profile, vehicle, 1, &sink);
  }
  rosbag::Bag bag(dir.file("flight.bag"), rosbag::bagmode::Read);
  std::map<long, pe::SimTruth> truths;  // by stamp in units of 40 ms
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/sim/truth"))) {
    truths[std::lround((m.getTime() - ros::Time(pe::kSimulatedBagStartSec)).toSec() * 25.0)] =
        *m.instantiate<pe::SimTruth>();
  }
  const auto truthAt = [&](const ros::Time& stamp) -> const pe::SimTruth& {
    return truths.at(std::lround((stamp - ros::Time(pe::kSimulatedBagStartSec)).toSec() * 25.0));
  };
  const pe::sim::FlightSensorParams sensors;
  const pe::sim::AirConditions air = params.bench.air;
  std::map<std::string, int> checked;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    const std::string topic = m.getTopic();
    const pe::SimTruth& truth = truthAt(m.getTime());
    // Within 20 ms of the truth: at 2 m/s, 4 cm.
    const double height_slack = 0.04;
    if (topic == "/mavros/imu/static_pressure") {
      const auto msg = m.instantiate<sensor_msgs::FluidPressure>();
      EXPECT_EQ(msg->header.frame_id, "base_link");
      EXPECT_NEAR(msg->fluid_pressure, air.pressureAtHeightPa(truth.height_m), 5.0 * sensors.pressure_sigma_pa + 0.5);
      EXPECT_NEAR(msg->variance, sensors.pressure_sigma_pa * sensors.pressure_sigma_pa, 1e-12);
    } else if (topic == "/mavros/imu/temperature_baro") {
      EXPECT_NEAR(m.instantiate<sensor_msgs::Temperature>()->temperature, air.temperature_c,
                  5.0 * sensors.air_temperature_sigma_c);
    } else if (topic == "/mavros/rangefinder/rangefinder") {
      const auto msg = m.instantiate<sensor_msgs::Range>();
      EXPECT_EQ(msg->radiation_type, sensor_msgs::Range::INFRARED);
      if (std::isinf(msg->range)) {
        // REP-117: -inf below the minimum range, which the gear's 0.12 m is 2 sigma above.
        EXPECT_LT(msg->range, 0.0f);
        EXPECT_LT(truth.height_m, msg->min_range + 5.0 * sensors.rangefinder_sigma_m);
      } else {
        EXPECT_NEAR(msg->range, truth.height_m, height_slack + 5.0 * sensors.rangefinder_sigma_m);
      }
    } else if (topic == "/motor_temperature") {
      const auto msg = m.instantiate<sensor_msgs::Temperature>();
      EXPECT_EQ(msg->header.frame_id.rfind("rotor_", 0), 0u) << msg->header.frame_id;
      const double hottest = *std::max_element(truth.motor_temperature_c.begin(), truth.motor_temperature_c.end());
      EXPECT_NEAR(msg->temperature, hottest, 5.0 * sensors.motor_temperature_sigma_c + 0.1);
    } else if (topic == "/mavros/local_position/pose") {
      const auto msg = m.instantiate<geometry_msgs::PoseStamped>();
      EXPECT_EQ(msg->header.frame_id, "map");
      // Origin at base_link's start, 0.119 m up (the gear sunk by the weight).
      EXPECT_NEAR(msg->pose.position.z, truth.height_m - 0.119, height_slack + 5.0 * sensors.position_sigma_m);
    } else if (topic == "/mavros/local_position/velocity_local") {
      const auto msg = m.instantiate<geometry_msgs::TwistStamped>();
      EXPECT_EQ(msg->header.frame_id, "map");
      EXPECT_NEAR(msg->twist.linear.z, truth.vertical_speed_m_s, 0.2 + 5.0 * sensors.velocity_sigma_m_s);
    } else if (topic == "/mavros/battery") {
      const auto msg = m.instantiate<sensor_msgs::BatteryState>();
      EXPECT_NEAR(msg->voltage, truth.battery_voltage_v, 5.0 * sensors.battery_voltage_sigma_v + 0.01);
      // PX4 through MAVROS: negative while discharging (the truth is positive).
      EXPECT_NEAR(-msg->current, truth.battery_current_a, 5.0 * sensors.battery_current_sigma_a + 0.01);
    } else if (topic == "/mavros/imu/data") {
      const auto msg = m.instantiate<sensor_msgs::Imu>();
      EXPECT_EQ(msg->header.frame_id, "base_link");
      const Eigen::Quaterniond q(msg->orientation.w, msg->orientation.x, msg->orientation.y, msg->orientation.z);
      EXPECT_NEAR(q.norm(), 1.0, 1e-6);
      EXPECT_LT(q.toRotationMatrix()(2, 2), 1.0 + 1e-9);
      EXPECT_GT(q.toRotationMatrix()(2, 2), std::cos(0.2));  // level within the controller's tilts
      EXPECT_GT(msg->orientation_covariance[0], 0.0);       // an orientation is present (REP-145)
    } else {
      continue;
    }
    ++checked[topic];
  }
  EXPECT_EQ(checked.size(), 8u);
  for (const auto& [topic, count] : checked) EXPECT_GT(count, 10) << topic;
}

TEST(SimulateCommand, WritesAFlightBagAndItsManifest) {
  TempDir dir;
  writeFile(dir.file("profile.yaml"), shortProfile());
  writeFile(dir.file("effects.yaml"), "thrust_loss: {fraction: 0.03}\n");
  testing::internal::CaptureStdout();
  const int code =
      runCommand({"flight", "--params", repoPath("config/sim/e300_dji2212_dji9443.yaml"), "--profile",
                  dir.file("profile.yaml"), "--effects", dir.file("effects.yaml"), "--bag", dir.file("flight.bag"),
                  "--manifest", dir.file("flight.manifest.yaml"), "--compression", "lz4", "--seed", "3"});
  const std::string out = testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0) << out;
  const pe::FlightManifest manifest = pe::loadFlightManifest(dir.file("flight.manifest.yaml"));
  ASSERT_EQ(manifest.flights.size(), 1u);
  EXPECT_EQ(manifest.flights[0].log, "flight.bag");
  ASSERT_EQ(manifest.flights[0].segments.size(), 1u);
  EXPECT_EQ(manifest.flights[0].segments[0].mass_kg, 1.315);
  EXPECT_TRUE(fs::exists(pe::resolveLogPath(dir.file("flight.manifest.yaml"), manifest.flights[0].log)));
  const std::string text = pe::readTextFile(dir.file("flight.manifest.yaml"));
  EXPECT_NE(text.find("# Effects: thrust_loss(fraction=0.03)\n"), std::string::npos) << text;
}

TEST(SimulateCommand, WritesAirborneManifestSegmentsWhenAsked) {
  // Take-off at 1 s, climb from 3 s (after the spin-up): the segment starts 3 s (settle) later, at
  // 6 s; the landing starts from 1 m at 11.88 s and brings the feet within 0.2 m of the ground
  // (base_link at 0.32 m) 0.68 s later.
  TempDir dir;
  std::string profile = shortProfile();
  profile.replace(profile.find("manifest: {settle_s: 3}"), 23, "manifest: {settle_s: 3, spans: airborne}");
  writeFile(dir.file("profile.yaml"), profile);
  testing::internal::CaptureStdout();
  const int code = runCommand({"flight", "--params", repoPath("config/sim/e300_dji2212_dji9443.yaml"), "--profile",
                               dir.file("profile.yaml"), "--bag", dir.file("flight.bag"), "--manifest",
                               dir.file("flight.manifest.yaml")});
  const std::string out = testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("simulate flight: 1 airborne segments -> "), std::string::npos) << out;
  const pe::FlightManifest manifest = pe::loadFlightManifest(dir.file("flight.manifest.yaml"));
  ASSERT_EQ(manifest.flights.at(0).segments.size(), 1u);
  EXPECT_DOUBLE_EQ(manifest.flights[0].segments[0].start_s, 6.0);
  EXPECT_DOUBLE_EQ(manifest.flights[0].segments[0].end_s, 12.56);
  EXPECT_EQ(manifest.flights[0].segments[0].mass_kg, 1.315);
  EXPECT_NE(pe::readTextFile(dir.file("flight.manifest.yaml"))
                .find("# Airborne segments from 3 s after each lift-off to 0.2 m above touchdown; times in seconds "
                      "from the bag's first message.\n"),
            std::string::npos);
}

TEST(SimulateCommand, WritesABenchCsv) {
  TempDir dir;
  testing::internal::CaptureStdout();
  const int code =
      runCommand({"bench", "--params", repoPath("config/sim/e300_dji2212_dji9443.yaml"), "--experiment", "pwm_sweep",
                  "--voltage", "11.1", "--voltage", "12.6", "--pwm-range", "1300", "1800", "--pwm-step", "10",
                  "--output", dir.file("sweep.csv"), "--truth", dir.file("truth.csv")});
  const std::string out = testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  EXPECT_EQ(out, "simulate bench: 102 rows of pwm_sweep -> " + dir.file("sweep.csv") + "\n");
  const std::string csv = pe::readTextFile(dir.file("sweep.csv"));
  EXPECT_NE(csv.find("# noise_sigma_current_a: 0.106\n"), std::string::npos);
  EXPECT_NE(pe::readTextFile(dir.file("truth.csv")).find("# noise_sigma_current_a: 0\n"), std::string::npos);
}

TEST(SimulateCommand, RefusesBadInputsWithOneLine) {
  TempDir dir;
  writeFile(dir.file("profile.yaml"), shortProfile());
  writeFile(dir.file("wind.yaml"), "wind: {speed_m_s: 3}\n");
  const std::string params = repoPath("config/sim/e300_dji2212_dji9443.yaml");
  const auto refusal = [](std::vector<std::string> args) {
    testing::internal::CaptureStderr();
    const int code = runCommand(std::move(args));
    const std::string err = testing::internal::GetCapturedStderr();
    return std::to_string(code) + " " + err;
  };
  EXPECT_EQ(refusal({"flight", "--params", params, "--profile", dir.file("profile.yaml"), "--effects",
                     dir.file("wind.yaml"), "--bag", dir.file("f.bag")}),
            "1 simulate flight: " + dir.file("wind.yaml") +
                ":1: wind: unknown key (allowed: supply_resistance, air_density, ground_effect, thrust_loss, "
                "motor_temperature, climb_inflow, esc_offset, translational_lift)\n");
  writeFile(dir.file("impossible.yaml"), shortProfile() + "  - {type: hover, duration_s: 5}\n");
  EXPECT_EQ(
      refusal({"flight", "--params", params, "--profile", dir.file("impossible.yaml"), "--bag", dir.file("f.bag")}),
      "1 simulate flight: " + dir.file("impossible.yaml") +
          ":15: segments[4].type: hover on the ground (take off first)\n");
  EXPECT_EQ(refusal({"flight", "--params", dir.file("missing.yaml"), "--profile", dir.file("profile.yaml"), "--bag",
                     dir.file("f.bag")}),
            "1 simulate flight: " + dir.file("missing.yaml") + ": cannot open file\n");
  EXPECT_EQ(refusal({"flight", "--params", params, "--profile", dir.file("profile.yaml"), "--bag",
                     dir.file("no/such/dir/f.bag")}),
            "1 simulate flight: " + dir.file("no/such/dir/f.bag") +
                ": Error opening file: " + dir.file("no/such/dir/f.bag.active") + "\n");
  EXPECT_EQ(refusal({"bench", "--params", params, "--experiment", "pwm_sweep", "--pwm-range", "1900", "1200",
                     "--output", dir.file("b.csv")}),
            "1 simulate bench: --pwm-range: [1900, 1200] is not a range within 800..2200 us\n");
  EXPECT_EQ(refusal({"bench", "--params", params, "--experiment", "pwm_sweep", "--pwm-step", "1e-7", "--output",
                     dir.file("b.csv")}),
            "1 simulate bench: --pwm-step: 1e-07 gives 7000000001 pulse widths from 1200 to 1900 us (at most 1e+06)\n");
  EXPECT_FALSE(fs::exists(dir.file("b.csv")));
}

TEST(SimulateCommand, ARefusedFlightLeavesNoBagBehind) {
  TempDir dir;
  const std::string params = repoPath("config/sim/e300_dji2212_dji9443.yaml");
  const std::string bag = dir.file("f.bag");
  writeFile(bag, "an earlier bag");
  const auto refusal = [&](const std::string& profile) {
    writeFile(dir.file("profile.yaml"), profile);
    testing::internal::CaptureStderr();
    const int code = runCommand({"flight", "--params", params, "--profile", dir.file("profile.yaml"), "--bag", bag});
    return std::to_string(code) + " " + testing::internal::GetCapturedStderr();
  };
  // Refused before flying: the bag is never opened.
  std::string heavy = shortProfile();
  heavy.replace(heavy.find("{length_m: 1.0,"), 15, "{length_m: 0.3,");
  const std::string wait = "  - {type: wait, duration_s: 1}\n";
  heavy.replace(heavy.find(wait), wait.size(), wait + "  - {type: payload, mass_kg: 1.5, duration_s: 1}\n");
  EXPECT_EQ(refusal(heavy), "1 simulate flight: " + dir.file("profile.yaml") +
                                ": segments[1].mass_kg: 2.82 kg needs 6.9 N per rotor, more than 80 % of the 6.71 N "
                                "each gives at 1950 us from 12.3 V\n");
  // Refused in flight: the bag written so far is removed.
  std::string short_battery = shortProfile();
  short_battery.replace(short_battery.find("battery_initial_soc: 0.9"), 24, "battery_initial_soc: 0.025");
  EXPECT_EQ(refusal(short_battery), "1 simulate flight: " + dir.file("profile.yaml") +
                                        ": vehicle.battery_initial_soc: the battery is empty 8.88 s into the flight\n");
  EXPECT_TRUE(pe::readTextFile(bag) == "an earlier bag");
  EXPECT_FALSE(fs::exists(bag + ".active"));
}

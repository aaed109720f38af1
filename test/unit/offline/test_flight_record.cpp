// estimate's flight.yaml, which fleet reads: it reads back to the last bit (NaN figures as absent
// keys) and refuses what is not a flight record with one line naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/offline/flight_record.h"

namespace pe = propulsion_estimator;
namespace offline = propulsion_estimator::offline;

namespace {

offline::FlightRecord aRecord() {
  offline::FlightRecord r;
  r.source = "logs/v03/flight \"12\": #1.bag";
  r.duration_s = 71.30000000000001;
  r.empty_mass_kg = 1.3151234567890123;
  offline::HoverEpisode first;
  first.start_s = 9.1;
  first.end_s = 31.05;
  first.total_mass_kg = 1.4821234567;
  first.mass_std_kg = 0.0041;
  first.payload_kg = 0.167;
  first.window_s = 10.0;
  first.voltage_v = 15.91;
  first.thrust_to_weight = 2.31;
  first.max_additional_payload_kg = 0.52;
  offline::HoverEpisode second = first;
  second.start_s = 40.0;
  second.total_mass_kg = pe::kNaN;  // too short to average
  second.payload_kg = pe::kNaN;
  second.max_additional_payload_kg = pe::kNaN;
  r.hovers = {first, second};
  r.motor_health.judged = true;
  r.motor_health.blocks = 10;
  r.motor_health.flagged_channel = 3;
  r.motor_health.yaw_imbalance = -0.0123;
  r.motor_health.yaw_imbalance_std = 0.002;
  r.motor_health.cg_offset_x_m = 0.004;
  r.motor_health.cg_offset_y_m = -0.0021;
  r.motor_health.motors = {{1, 0.004, 0.006}, {2, -0.01, 0.0061}, {3, 0.081234567890123, 0.0059}, {4, 0.0, 0.006}};
  r.flagged_channels = {3, 1};
  r.pack_resistance_ohm = 0.0312345678901;
  r.pack_resistance_std_ohm = 0.0021;
  r.esc_verdict = "propeller";
  r.esc_flagged_channel = 3;
  r.supply_resistance_ohm = pe::kNaN;
  r.esc_flags = {"propeller on channel 3"};
  r.log_damage = "logs/v03/flight.bag: at byte 299956: D message: truncated (41 of 274 bytes)";
  r.warnings = {"the motor-health check flagged channel 3 (\"its share\": beyond the spread)", "a line\nof two"};
  return r;
}

bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

void expectSame(const offline::FlightRecord& a, const offline::FlightRecord& b) {
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.duration_s, b.duration_s);
  EXPECT_TRUE(same(a.empty_mass_kg, b.empty_mass_kg));
  ASSERT_EQ(a.hovers.size(), b.hovers.size());
  for (std::size_t i = 0; i < a.hovers.size(); ++i) {
    const offline::HoverEpisode& x = a.hovers[i];
    const offline::HoverEpisode& y = b.hovers[i];
    EXPECT_TRUE(same(x.start_s, y.start_s) && same(x.end_s, y.end_s) && same(x.total_mass_kg, y.total_mass_kg) &&
                same(x.mass_std_kg, y.mass_std_kg) && same(x.payload_kg, y.payload_kg) &&
                same(x.window_s, y.window_s) && same(x.voltage_v, y.voltage_v) &&
                same(x.thrust_to_weight, y.thrust_to_weight) &&
                same(x.max_additional_payload_kg, y.max_additional_payload_kg))
        << "hover " << i;
  }
  const pe::MotorHealthVerdict& v = a.motor_health;
  const pe::MotorHealthVerdict& w = b.motor_health;
  EXPECT_EQ(v.judged, w.judged);
  EXPECT_EQ(v.unavailable, w.unavailable);
  EXPECT_EQ(v.blocks, w.blocks);
  EXPECT_EQ(v.flagged_channel, w.flagged_channel);
  EXPECT_TRUE(same(v.yaw_imbalance, w.yaw_imbalance) && same(v.yaw_imbalance_std, w.yaw_imbalance_std));
  EXPECT_TRUE(same(v.cg_offset_x_m, w.cg_offset_x_m) && same(v.cg_offset_y_m, w.cg_offset_y_m));
  ASSERT_EQ(v.motors.size(), w.motors.size());
  for (std::size_t k = 0; k < v.motors.size(); ++k) {
    EXPECT_EQ(v.motors[k].channel, w.motors[k].channel);
    EXPECT_TRUE(same(v.motors[k].thrust_gap, w.motors[k].thrust_gap));
    EXPECT_TRUE(same(v.motors[k].thrust_gap_std, w.motors[k].thrust_gap_std));
  }
  EXPECT_EQ(a.flagged_channels, b.flagged_channels);
  EXPECT_TRUE(same(a.pack_resistance_ohm, b.pack_resistance_ohm));
  EXPECT_TRUE(same(a.pack_resistance_std_ohm, b.pack_resistance_std_ohm));
  EXPECT_EQ(a.esc_verdict, b.esc_verdict);
  EXPECT_EQ(a.esc_flagged_channel, b.esc_flagged_channel);
  EXPECT_TRUE(same(a.supply_resistance_ohm, b.supply_resistance_ohm));
  EXPECT_EQ(a.esc_flags, b.esc_flags);
  EXPECT_EQ(a.log_damage, b.log_damage);
  EXPECT_EQ(a.warnings, b.warnings);
}

std::string refusal(const std::string& text) {
  try {
    offline::parseFlightRecord(text, "flight.yaml");
  } catch (const pe::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace

TEST(FlightRecord, ReadsBackToTheLastBitWithItsNaNsAbsent) {
  const offline::FlightRecord record = aRecord();
  const std::string text = offline::flightRecordText(record);
  expectSame(record, offline::parseFlightRecord(text, "flight.yaml"));
  EXPECT_EQ(text.find("supply_resistance_ohm"), std::string::npos) << text;
  EXPECT_EQ(offline::flightRecordText(offline::parseFlightRecord(text, "flight.yaml")), text);
}

TEST(FlightRecord, AnUnjudgedFlightReadsBackWithWhyNot) {
  offline::FlightRecord record;
  record.source = "a.ulg";
  record.motor_health.unavailable = "no rotor geometry (give --urdf or --frame)";
  expectSame(record, offline::parseFlightRecord(offline::flightRecordText(record), "flight.yaml"));
}

TEST(FlightRecord, RefusesWhatIsNotOneWithTheKeyNamed) {
  const std::string text = offline::flightRecordText(aRecord());
  EXPECT_NE(refusal(replaced(text, "format: propulsion_estimator/flight_record", "format: pack_file")).find(
                "flight.yaml:3: format: 'pack_file' is not propulsion_estimator/flight_record"),
            std::string::npos);
  EXPECT_NE(refusal(replaced(text, "version: 1", "version: 2"))
                .find("version: 2 is not 1, the version this build reads"),
            std::string::npos);
  EXPECT_NE(refusal(replaced(text, "{channel: 2,", "{channel: 0,"))
                .find("motor_health.motors[1].channel: 0 is not a channel (they count from 1)"),
            std::string::npos);
  EXPECT_NE(refusal(replaced(text, "verdict: propeller", "verdict: wobbly")).find("esc.verdict"), std::string::npos);
  EXPECT_NE(refusal(replaced(text, "flagged_channels: [3, 1]", "flagged_channels: [3, 1.5]"))
                .find("flagged_channels: 1.5 is not a channel"),
            std::string::npos);
  EXPECT_NE(refusal(replaced(text, "pack:", "battery:")).find("battery"), std::string::npos);
  EXPECT_NE(refusal(text + "warnings_too: []\n").find("warnings_too"), std::string::npos);
  EXPECT_NE(refusal(replaced(text, "duration_s: 71.30000000000001", "duration_s: -1")).find("duration_s: -1 is negative"),
            std::string::npos);
}

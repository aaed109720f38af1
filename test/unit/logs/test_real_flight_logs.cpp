// Real public flight logs (test/data/, with their licences), cut to the messages the readers use:
// the signals each holds are listed, a signal its firmware lacks is said in one line, and the
// diagnosis runs on what is there.
#include <gtest/gtest.h>

#include <algorithm>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/logs/dataflash_flight_reader.h"
#include "propulsion_estimator/logs/ulog_flight_reader.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

bool hasNote(const pe::FlightStreams& streams, const std::string& note) {
  return std::find(streams.notes.begin(), streams.notes.end(), note) != streams.notes.end();
}

}  // namespace

// PX4 v1.11 on a CubeOrange (pyulog's sample_log_small.ulg): two battery and two actuator_outputs
// instances, no distance sensor and no ESC telemetry.
TEST(RealFlightLogs, Px4UlogIsReadAndDiagnosed) {
  const std::string path = repoPath("test/data/px4_pyulog_sample_log_small/sample_log_small_cut.ulg");
  const pe::UlogFlightReader reader(path);
  EXPECT_EQ(reader.refusal(), "");
  EXPECT_EQ(reader.file().infoText("ver_hw"), "CUBEPILOT_CUBEORANGE");
  pe::FlightLogOptions options;
  options.motors = 4;
  const pe::FlightStreams streams = reader.read(options);
  for (const std::string& note : streams.notes) std::cout << "  " << note << "\n";
  EXPECT_EQ(streams.rc_out.size(), 65u);  // instance 0 only
  EXPECT_EQ(streams.battery.size(), 21u);
  EXPECT_GT(streams.imu.size(), 1000u);
  EXPECT_GT(streams.altitude_m.size(), 600u);
  EXPECT_EQ(streams.input(pe::input::Scalar::kStaticPressure).size(), 120u);
  EXPECT_TRUE(streams.input(pe::input::Scalar::kRangefinder).empty());
  EXPECT_TRUE(hasNote(streams, "rangefinder: not in this log (no distance_sensor)"));
  EXPECT_TRUE(hasNote(streams, "motor_temperature: not in this log (no esc_status)"));
  // Physical sense, in the package's frames: a battery of a few cells, the barometer near sea level
  // pressure, the specific force up about g when still.
  EXPECT_GT(streams.battery[5].voltage_v, 6.0);
  EXPECT_LT(streams.battery[5].voltage_v, 26.0);
  EXPECT_NEAR(streams.input(pe::input::Scalar::kStaticPressure)[5].value, 1.0e5, 1.5e4);
  const pe::ImuReading& first = streams.imu.front();
  EXPECT_NEAR((first.orientation * first.specific_force_m_s2).z(), 9.81, 1.5);
  for (const pe::RcOutFrame& frame : streams.rc_out) {
    for (int k = 0; k < 4; ++k) EXPECT_TRUE(frame.pwm_us[k] == 0.0 || (frame.pwm_us[k] >= 800 && frame.pwm_us[k] <= 2200));
  }

  // Its mass was not weighed: the diagnosis runs on a segment of an assumed mass, to show the
  // flight goes through; its figures are no finding.
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  std::vector<pe::Flight> flights(1);
  flights[0].name = "sample_log_small";
  flights[0].streams = streams;
  flights[0].segments.push_back({1.0, reader.durationS() - 1.0, 1.5});
  const pe::gap::Diagnosis diagnosis =
      pe::gap::diagnoseGap(model, pe::Vehicle::upwardRotors(4), flights, pe::gap::DiagnosisConfig{}, {});
  std::cout << "  diagnosis: " << diagnosis.overall.samples << " samples; " << diagnosis.steady_data_shortfall << "\n";
  // 6.5 s of log: a few steady seconds, far too few stretches for the selection's test.
  EXPECT_EQ(diagnosis.blocks, 4);
  EXPECT_EQ(diagnosis.steady_data_shortfall,
            "not enough steady data: 4 quasi-steady 1 s blocks (0 transient left out) in 1 stretch of up to 10 s; "
            "the selection's sign-flip test needs 7 to reach p < 0.01, so no effect can be named");
  EXPECT_TRUE(diagnosis.selected.empty());
}

// ArduPlane 4.2.3 (PyFlightCoach/FlightData's center_0003.bin), logged with attitude and the EKF
// only: it lacks the motor outputs the diagnosis needs, and says so in one line.
TEST(RealFlightLogs, ArduPilotLogSaysWhichSignalItLacks) {
  const std::string path = repoPath("test/data/arduplane_flightdata_center_0003/center_0003_cut.bin");
  const pe::DataflashFlightReader reader(path);
  EXPECT_EQ(reader.refusal(), "");
  EXPECT_GT(reader.durationS(), 40.0);
  pe::FlightLogOptions options;
  options.motors = 4;
  try {
    reader.read(options);
    ADD_FAILURE() << "read without motor outputs";
  } catch (const pe::DataError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": rc_out: no RCOU messages (a required signal)");
    std::cout << "  " << e.what() << "\n";
  }
  // What it has: attitude and the EKF's height, read by their labels (ATT in centidegrees, 'c').
  const auto xkf1 = reader.file().typeNamed("XKF1");
  ASSERT_TRUE(xkf1);
  const auto pd = reader.file().column(*xkf1, "PD");
  ASSERT_TRUE(pd);
  int messages = 0;
  for (const pe::dataflash::Message& message : reader.file().messages()) messages += message.type == *xkf1;
  EXPECT_EQ(messages, 1034);
}

// ArduCopter 3.3-dev on a Pixhawk quad (DroneKit-LA's log171.bin), in the layout before
// ArduPilot 3.3: TimeMS, RCOU Ch1..Ch4, the battery in CURR (hundredths), the EKF's height in
// EKF1. Every required signal is there; the rangefinder and ESC telemetry are not.
TEST(RealFlightLogs, ArduCopterLogIsReadAndDiagnosed) {
  const std::string path = repoPath("test/data/arducopter_dronekit_la_log171/log171_cut.bin");
  const pe::DataflashFlightReader reader(path);
  EXPECT_EQ(reader.refusal(), "");
  pe::FlightLogOptions options;
  options.motors = 4;
  const pe::FlightStreams streams = reader.read(options);
  for (const std::string& note : streams.notes) std::cout << "  " << note << "\n";
  EXPECT_TRUE(hasNote(streams, "rc_out: RCOU Ch1..Ch4 (us)"));
  EXPECT_TRUE(hasNote(streams, "battery: CURR Volt, Curr (hundredths)"));
  EXPECT_TRUE(hasNote(streams, "pose, velocity: EKF1 -PD, -VD, VE, VN"));
  EXPECT_TRUE(hasNote(streams, "rangefinder: not in this log (no RFND)"));
  EXPECT_TRUE(hasNote(streams, "motor_temperature: not in this log (no ESC)"));
  EXPECT_EQ(streams.rc_out.size(), 11916u);
  EXPECT_EQ(streams.battery.size(), 2384u);
  EXPECT_EQ(streams.altitude_m.size(), 2383u);
  EXPECT_EQ(streams.input(pe::input::Scalar::kStaticPressure).size(), 2383u);
  EXPECT_GT(streams.imu.size(), 2000u);
  EXPECT_TRUE(streams.input(pe::input::Scalar::kRangefinder).empty());
  // Physical sense: a 4S battery (16.5 V full, 15.2-16 V under the hover's 14 A), motors idle at
  // 1000 us on the ground, the specific force up about g.
  double max_current_a = 0.0;
  for (const pe::BatteryReading& battery : streams.battery) {
    EXPECT_GT(battery.voltage_v, 14.5);
    EXPECT_LT(battery.voltage_v, 16.9);
    max_current_a = std::max(max_current_a, battery.current_a);
  }
  EXPECT_GT(max_current_a, 14.0);
  EXPECT_LT(max_current_a, 60.0);
  EXPECT_EQ(streams.rc_out.front().pwm_us[0], 1000.0);
  const pe::ImuReading& first = streams.imu.front();
  EXPECT_NEAR((first.orientation * first.specific_force_m_s2).z(), 9.81, 1.0);

  // Unweighed: the airborne 153 s as one segment of an assumed 1.5 kg, to show what the diagnosis
  // says of a real manual flight. Half of its seconds are steady enough, in more stretches than
  // the test needs; with one segment nothing can be held out, and the thesis' 3S surfaces do not
  // reach this 4S vehicle's voltage: every block lies outside the model's domain.
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  std::vector<pe::Flight> flights(1);
  flights[0].name = "log171";
  flights[0].streams = streams;
  flights[0].segments.push_back({75.0, 228.0, 1.5});
  const pe::gap::Diagnosis diagnosis =
      pe::gap::diagnoseGap(model, pe::Vehicle::upwardRotors(4), flights, pe::gap::DiagnosisConfig{}, {});
  std::cout << "  diagnosis: " << diagnosis.blocks << " quasi-steady blocks, " << diagnosis.transient_blocks
            << " transient\n";
  EXPECT_GT(diagnosis.blocks, 60);
  EXPECT_GT(diagnosis.transient_blocks, 60);
  EXPECT_EQ(diagnosis.steady_data_shortfall, "");
  EXPECT_TRUE(diagnosis.selected.empty());
  EXPECT_NE(std::find(diagnosis.problems.begin(), diagnosis.problems.end(),
                      "one weighed segment only: nothing can be held out, so no effect is selected"),
            diagnosis.problems.end());
  const auto region = std::find_if(diagnosis.where.begin(), diagnosis.where.end(),
                                   [](const pe::gap::Breakdown& b) { return b.name == "operating_region"; });
  ASSERT_NE(region, diagnosis.where.end());
  ASSERT_EQ(region->bins.size(), 1u);
  EXPECT_EQ(region->bins[0].label, "outside the model's domain");
}

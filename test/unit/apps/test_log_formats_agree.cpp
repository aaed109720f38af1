// One simulated flight written as a rosbag, a PX4 ULog in PX4 1.12's and in the newer layout and an
// ArduPilot DataFlash log at once (one simulation, four writers), each read through the flight-log
// registry as diagnose_gap reads it: the four diagnoses select the same effects with the same
// parameters; the ESC telemetry of every log gives the RPM view the same blocks and the replayed
// live model check the same judgements.
#include <gtest/gtest.h>

#include <filesystem>

#include "propulsion_estimator/bag/bag_flight_sink.h"
#include "propulsion_estimator/bag/flight_bag_reader.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/gap/model_check_replay.h"
#include "propulsion_estimator/logs/dataflash_flight_reader.h"
#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/logs/ulog_flight_reader.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/sim/flight/dataflash_flight_sink.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/flight/ulog_flight_sink.h"
#include "propulsion_estimator/sim/physics/sim_effects_yaml.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "simulated_flight_logs.h"

namespace pe = propulsion_estimator;
namespace fs = std::filesystem;

TEST(LogFormats, GiveTheSameDiagnosisOfOneFlight) {
  const fs::path dir = fs::temp_directory_path() / ("pe_formats_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const pe::sim::FlightProfile profile = pe::sim::loadFlightProfileFile(repoPath("config/demo/demo_flight_profile.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
  pe::writeTextFile((dir / "effects.yaml").string(), "thrust_loss: {fraction: 0.06}\n");
  pe::sim::FlightResult result;
  {
    pe::BagFlightSink bag((dir / "flight.bag").string(), rosbag::compression::Uncompressed);
    pe::sim::UlogFlightSink ulog(pe::sim::UlogLayout::kPx4v1_12, profile.autopilot.pwm_min_us,
                                 profile.autopilot.pwm_max_us);
    pe::sim::UlogFlightSink newer_ulog(pe::sim::UlogLayout::kPx4v1_14, profile.autopilot.pwm_min_us,
                                       profile.autopilot.pwm_max_us);
    pe::sim::DataflashFlightSink dataflash;
    TeeFlightSink ulogs(&ulog, &newer_ulog);
    TeeFlightSink logs(&ulogs, &dataflash);
    TeeFlightSink all(&bag, &logs);
    result = pe::sim::simulateFlight(pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")),
                                     pe::sim::loadSimEffectsFile((dir / "effects.yaml").string()), profile, vehicle, 3,
                                     &all);
    bag.close();
    ulog.save((dir / "flight.ulg").string());
    newer_ulog.save((dir / "flight_newer.ulg").string());
    dataflash.save((dir / "flight.bin").string());
  }
  pe::FlightLogFormats formats;
  formats.add(pe::flightBagFormat());
  formats.add(pe::ulogFormat());
  formats.add(pe::dataflashFormat());
  pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  // The thesis hardware's rotor (695 g at 8844 rpm on the simulated bench), for the RPM view.
  pe::RpmThrust rpm_thrust;
  rpm_thrust.n_per_rpm2 = 8.72e-8;
  model.setRpmThrust(rpm_thrust);
  pe::FlightLogOptions options;
  options.motors = 4;
  std::vector<pe::gap::Diagnosis> diagnoses;
  std::vector<pe::gap::ModelCheckReplay> replays;
  for (const char* name : {"flight.bag", "flight.ulg", "flight.bin", "flight_newer.ulg"}) {
    const auto reader = formats.open((dir / name).string());
    // The newer layout logs actuator_motors only: the user gives the PWM range it maps onto.
    pe::FlightLogOptions read_options = options;
    if (std::string(name) == "flight_newer.ulg") {
      read_options.pwm_min_us = profile.autopilot.pwm_min_us;
      read_options.pwm_max_us = profile.autopilot.pwm_max_us;
    }
    const std::vector<pe::Flight> flights = {{name, reader->read(read_options), result.segments, ""}};
    diagnoses.push_back(pe::gap::diagnoseGap(model, vehicle, flights, pe::gap::DiagnosisConfig{}, {}));
    replays.push_back(pe::gap::replayModelCheck(model, vehicle, flights.front().streams));
  }
  fs::remove_all(dir);
  // What the diagnosis names: the selected effects and each ambiguous group (one flight at one
  // current cannot always tell a thrust loss from its look-alikes); the thrust loss among them.
  const auto named = [](const pe::gap::Diagnosis& d) {
    std::vector<std::vector<pe::effects::Kind>> groups;
    for (pe::effects::Kind kind : d.selected) groups.push_back({kind});
    for (const pe::gap::Ambiguity& group : d.ambiguous) groups.push_back(group.kinds);
    return groups;
  };
  const pe::gap::Diagnosis& bag = diagnoses[0];
  EXPECT_GT(bag.rpm_view_blocks, 0);
  EXPECT_EQ(diagnoses[1].rpm_view_blocks, bag.rpm_view_blocks);
  EXPECT_EQ(diagnoses[3].rpm_view_blocks, bag.rpm_view_blocks);
  EXPECT_EQ(diagnoses[2].rpm_view_blocks, bag.rpm_view_blocks);
  // The live model check replayed from each log: the ULogs' telemetry judged as the bag's.
  EXPECT_GT(replays[0].judgements, 0);
  EXPECT_EQ(replays[1].judgements, replays[0].judgements);
  EXPECT_EQ(replays[1].verdicts, replays[0].verdicts);
  // The newer layout logs stopped motors as NaN, read as not driven (0 us) as the bag's disarmed
  // outputs are: the check judges what it judges on the bag.
  EXPECT_EQ(replays[3].judgements, replays[0].judgements);
  EXPECT_EQ(replays[3].verdicts, replays[0].verdicts);
  EXPECT_TRUE(replays[2].telemetry);
  EXPECT_EQ(replays[2].judgements, replays[0].judgements);
  EXPECT_EQ(replays[2].verdicts, replays[0].verdicts);
  ASSERT_EQ(named(bag).size(), 1u);
  ASSERT_EQ(named(bag)[0].front(), pe::effects::Kind::kThrustLoss);
  const double fraction = *bag.fitted.parameter(pe::effects::Kind::kThrustLoss);
  EXPECT_NEAR(fraction, 0.06, 0.01);
  for (std::size_t i = 1; i < diagnoses.size(); ++i) {
    const pe::gap::Diagnosis& other = diagnoses[i];
    EXPECT_EQ(other.selected, bag.selected) << i;
    EXPECT_EQ(named(other), named(bag)) << i;
    EXPECT_NEAR(*other.fitted.parameter(pe::effects::Kind::kThrustLoss), fraction, 1e-4 * fraction) << i;
    EXPECT_EQ(other.overall.samples, bag.overall.samples) << i;
    EXPECT_NEAR(other.overall.rmse_pct, bag.overall.rmse_pct, 1e-3) << i;
    EXPECT_NEAR(other.heldout.after_rmse_pct, bag.heldout.after_rmse_pct, 1e-3) << i;
  }
}

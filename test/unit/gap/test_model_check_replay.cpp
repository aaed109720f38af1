// The live model check replayed on logged flights (gap/model_check_replay.h): what estimator_node's
// ESC-telemetry check would have said, from a bag the simulator wrote with its ESC sensors (noise,
// gain errors, lost packets), read back as diagnose_gap reads it. A chipped propeller (thrust and
// torque down) is flagged on its own channel as "propeller"; a flight without a fault is judged and
// never flagged; a flight without telemetry is not judged. (A worn blade, thrust down at the torque
// of an intact one, turns as fast and draws as much as an intact one at the same command: the
// ESC's ratios cannot see it.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "propulsion_estimator/bag/bag_flight_sink.h"
#include "propulsion_estimator/bag/flight_bag_reader.h"
#include "propulsion_estimator/gap/model_check_replay.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace fs = std::filesystem;

namespace {

// A 20 s hover flown by PX4 or ArduPilot, written to a bag and read back; `weak_motor` 0 for none.
pe::FlightStreams flyToBag(const std::string& name, int weak_motor, bool px4, double esc_rate_hz = 10.0) {
  pe::sim::FlightProfile profile = pe::sim::loadFlightProfileFile(repoPath("config/sim/default_flight.yaml"));
  profile.autopilot.flavour = px4 ? pe::sim::AutopilotFlavour::kPx4 : pe::sim::AutopilotFlavour::kArduPilot;
  profile.segments = {{pe::sim::SegmentKind::kWait, 1.0, 0.0, 0.0, 0.0},
                      {pe::sim::SegmentKind::kTakeoff, 0.0, 2.0, 1.0, 0.0},
                      {pe::sim::SegmentKind::kHover, 20.0, 0.0, 0.0, 0.0},
                      {pe::sim::SegmentKind::kLand, 0.0, 0.0, 1.0, 0.0}};
  if (weak_motor > 0) {
    profile.faults.weak_propeller = pe::sim::PropellerFault{weak_motor, 0.9, pe::sim::PropellerDamage::kChipped};
  }
  const pe::sim::SimParams params = pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
  pe::sim::FlightSensorParams sensors;
  sensors.esc_telemetry_rate_hz = esc_rate_hz;
  const fs::path bag = fs::temp_directory_path() / ("pe_model_check_replay_" + name + ".bag");
  {
    pe::BagFlightSink sink(bag.string(), rosbag::compression::Uncompressed);
    pe::sim::simulateFlight(params, {}, profile, pe::loadVehicleUrdf(profile.vehicle.urdf_path), 31 + weak_motor,
                            &sink, sensors);
  }
  pe::FlightStreams streams = pe::FlightBagReader(bag.string()).read({}, 4);
  fs::remove(bag);
  return streams;
}

}  // namespace

TEST(ModelCheckReplay, FlagsAChippedPropellerOnItsChannelAndNothingWithoutAFault) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  for (bool px4 : {true, false}) {
    SCOPED_TRACE(px4 ? "PX4's ESCStatus" : "ArduPilot's ESCTelemetry");
    const pe::gap::ModelCheckReplay chipped = pe::gap::replayModelCheck(model, vehicle, flyToBag("chipped", 3, px4));
    EXPECT_TRUE(chipped.telemetry);
    EXPECT_GT(chipped.judgements, 5);
    EXPECT_EQ(chipped.flagged_channels, std::vector<int>{3});
    EXPECT_EQ(chipped.verdicts, std::vector<std::string>{"propeller"});
    EXPECT_GT(chipped.first_flag_s, 0.0);

    const pe::gap::ModelCheckReplay sound = pe::gap::replayModelCheck(model, vehicle, flyToBag("sound", 0, px4));
    EXPECT_TRUE(sound.telemetry);
    EXPECT_GT(sound.judgements, 5);
    EXPECT_TRUE(sound.verdicts.empty());
    EXPECT_TRUE(sound.flagged_channels.empty());
    EXPECT_TRUE(std::isnan(sound.first_flag_s));
  }
  const pe::gap::ModelCheckReplay none = pe::gap::replayModelCheck(model, vehicle, flyToBag("none", 0, true, 0.0));
  EXPECT_FALSE(none.telemetry);
  EXPECT_EQ(none.judgements, 0);
}

TEST(ModelCheckReplay, WritesOneLinePerFlight) {
  pe::gap::ModelCheckReplay flagged;
  flagged.telemetry = true;
  flagged.judgements = 12;
  flagged.verdicts = {"propeller"};
  flagged.flagged_channels = {3};
  flagged.first_flag_s = 17.5;
  pe::gap::ModelCheckReplay none;
  none.first_flag_s = pe::kNaN;
  const std::string yaml = pe::gap::modelCheckReplayYaml({"a.bag", "b.bag"}, {flagged, none});
  EXPECT_NE(yaml.find("{bag: a.bag, telemetry: true, judgements: 12, verdicts: [propeller], flagged: [3], "
                      "first_flag_s: 17.5}"),
            std::string::npos)
      << yaml;
  EXPECT_NE(yaml.find("{bag: b.bag, telemetry: false, judgements: 0, verdicts: [], flagged: [], first_flag_s: ~}"),
            std::string::npos)
      << yaml;
}

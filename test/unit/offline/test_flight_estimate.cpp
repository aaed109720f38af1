// The estimator's onboard session on a logged flight (offline/): what estimate runs on every log.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/offline/estimate_csv.h"
#include "propulsion_estimator/offline/estimate_summary.h"
#include "propulsion_estimator/offline/flight_estimate.h"
#include "propulsion_estimator/offline/flight_feed.h"
#include "propulsion_estimator/offline/yaml_parameter_source.h"
#include "propulsion_estimator/onboard/node_parameters.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "simulated_flight_logs.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::PropulsionModel thesisModel() { return pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml")); }

// A flight log's streams from the simulator's short flight (take off, 8 s of hover at 1 m, land).
pe::FlightStreams shortFlight() {
  RecordingFlightSink recorded, copy;
  simulateShortFlight(&recorded, &copy);
  pe::FlightStreams streams;
  streams.source = "short flight";
  streams.motors = 4;
  for (const auto& s : recorded.rc_out) {
    pe::RcOutFrame frame;
    frame.time_s = s.time_s;
    for (int k = 0; k < 4; ++k) frame.pwm_us[k] = s.channels[k];
    streams.rc_out.push_back(frame);
  }
  for (const auto& b : recorded.batteries) streams.battery.push_back({b.time_s, b.voltage_v, b.current_a});
  for (const auto& i : recorded.imus) streams.imu.push_back({i.time_s, i.orientation, i.linear_acceleration_m_s2});
  for (const auto& v : recorded.velocities) {
    streams.vertical_speed_m_s.push_back({v.time_s, v.linear_m_s.z()});
    streams.horizontal_velocity.push_back({v.time_s, v.linear_m_s.x(), v.linear_m_s.y()});
  }
  for (const auto& p : recorded.pressures) streams.input(pe::input::Scalar::kStaticPressure).push_back({p.time_s, p.value});
  for (const auto& t : recorded.air_temperatures) streams.input(pe::input::Scalar::kAirTemperature).push_back({t.time_s, t.value});
  return streams;
}

// `seconds` of a steady command on every motor at 50 Hz, the battery at `voltage_v`.
pe::FlightStreams steadyCommand(double pwm_us, double voltage_v, double seconds, double pwm_rise_us_per_s = 0.0) {
  pe::FlightStreams streams;
  streams.source = "steady.ulg";
  streams.motors = 4;
  for (int i = 0; i * 0.02 < seconds; ++i) {
    const double t = i * 0.02;
    pe::RcOutFrame frame;
    frame.time_s = t;
    for (int k = 0; k < 4; ++k) frame.pwm_us[k] = pwm_us + pwm_rise_us_per_s * t;
    streams.rc_out.push_back(frame);
    if (i % 5 == 0) streams.battery.push_back({t, voltage_v, -10.0});
  }
  return streams;
}

pe::offline::EstimateOptions optionsFor(const pe::Vehicle& vehicle) {
  pe::offline::EstimateOptions options;
  options.estimator = pe::offline::replayEstimatorConfig(vehicle);
  return options;
}

}  // namespace

TEST(FlightEstimate, FindsTheHoverOfASimulatedFlightAndItsMass) {
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  const pe::FlightStreams streams = shortFlight();
  const pe::offline::FlightEstimate estimate =
      pe::offline::estimateFlight(thesisModel(), vehicle, streams, optionsFor(vehicle));
  ASSERT_EQ(estimate.hovers.size(), 1u);
  const pe::offline::HoverEpisode& hover = estimate.hovers[0];
  // The simulator's physics is not the surfaces' (within 2 % in the hover band, test_sim_calibration).
  EXPECT_NEAR(hover.total_mass_kg, vehicle.empty_mass->mass_kg, 0.03 * vehicle.empty_mass->mass_kg);
  EXPECT_NEAR(hover.payload_kg, 0.0, 0.03 * vehicle.empty_mass->mass_kg);
  EXPECT_EQ(estimate.empty_mass_source, "urdf");
  EXPECT_GT(hover.end_s - hover.start_s, 3.0);
  EXPECT_LT(hover.end_s - hover.start_s, 8.5);
  EXPECT_GT(hover.thrust_to_weight, 1.6);
  // 10 rows a second of the log's clock, whatever the RCOut rate (25 Hz here).
  const double span_s = estimate.samples.back().time_s - estimate.samples.front().time_s;
  EXPECT_NEAR(static_cast<double>(estimate.samples.size()), 10.0 * span_s, 3.0);
}

TEST(FlightEstimate, GivesTheSameHoverMassAsTheEstimatorFedByHand) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  const pe::FlightStreams streams = steadyCommand(1500.0, 11.5, 20.0);
  pe::offline::EstimateOptions options = optionsFor(vehicle);
  options.estimator.empty_mass_kg = 1.0;
  const pe::offline::FlightEstimate estimate = pe::offline::estimateFlight(thesisModel(), vehicle, streams, options);
  ASSERT_EQ(estimate.hovers.size(), 1u);
  pe::OperatingPoint point;
  thesisModel().evaluate(1500.0, 11.5, &point);
  const double thrust_n = 4.0 * point.thrust_n;
  EXPECT_NEAR(estimate.hovers[0].total_mass_kg, thrust_n / 9.80665, 1e-6);
  EXPECT_NEAR(estimate.hovers[0].payload_kg, thrust_n / 9.80665 - 1.0, 1e-6);
  EXPECT_EQ(estimate.empty_mass_source, "parameter");
  EXPECT_TRUE(estimate.warnings.empty()) << estimate.warnings.front();
}

TEST(FlightEstimate, TwoHoversApartAreTwoEpisodes) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  pe::FlightStreams streams = steadyCommand(1500.0, 11.5, 15.0);
  pe::FlightStreams second = steadyCommand(1600.0, 11.5, 15.0);
  for (pe::RcOutFrame f : second.rc_out) streams.rc_out.push_back((f.time_s += 20.0, f));
  for (pe::BatteryReading b : second.battery) streams.battery.push_back((b.time_s += 20.0, b));
  const pe::offline::FlightEstimate estimate =
      pe::offline::estimateFlight(thesisModel(), vehicle, streams, optionsFor(vehicle));
  ASSERT_EQ(estimate.hovers.size(), 2u);
  EXPECT_LT(estimate.hovers[0].end_s, 15.0);
  EXPECT_GE(estimate.hovers[1].start_s, 20.0);
  EXPECT_GT(estimate.hovers[1].total_mass_kg, estimate.hovers[0].total_mass_kg * 1.1);
}

TEST(FlightEstimate, SaysWhyNoHoverWasFound) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  // A command ramping 100 us/s: the thrust is never steady within the hover window.
  const pe::offline::FlightEstimate estimate = pe::offline::estimateFlight(
      thesisModel(), vehicle, steadyCommand(1300.0, 11.5, 6.0, 100.0), optionsFor(vehicle));
  EXPECT_TRUE(estimate.hovers.empty());
  ASSERT_EQ(estimate.warnings.size(), 1u);
  EXPECT_EQ(estimate.warnings[0],
            "no hover found in 300 accepted messages: most often thrust unsteady beyond hover/max_thrust_rel_std "
            "(73 % of them)");
}

TEST(FlightEstimate, SaysWhenTheLogLiesOutsideTheModelsDomainWithBothRanges) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  // A 4-cell vehicle against the thesis' 3-cell model (10.5-12.6 V, clamped outside).
  const pe::offline::FlightEstimate estimate =
      pe::offline::estimateFlight(thesisModel(), vehicle, steadyCommand(1500.0, 15.1, 20.0), optionsFor(vehicle));
  ASSERT_FALSE(estimate.warnings.empty());
  EXPECT_EQ(estimate.warnings[0],
            "100.0 % of the motor samples lie outside the model's domain (the model covers 1200-1900 us at "
            "10.50-12.60 V; the log's battery reads 15.10-15.10 V, its motors 1500-1500 us while armed); outside: "
            "clamp: is this the right model for this vehicle?");
}

TEST(FlightEstimate, CountsTheRefusedInputsWithTheLastOne) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  pe::FlightStreams streams = steadyCommand(1500.0, 11.5, 20.0);
  streams.battery[3].voltage_v = -1.0;
  const pe::offline::FlightEstimate estimate =
      pe::offline::estimateFlight(thesisModel(), vehicle, streams, optionsFor(vehicle));
  ASSERT_FALSE(estimate.warnings.empty());
  EXPECT_EQ(estimate.warnings[0].rfind("inputs refused: 1 bad_voltage (the last: ", 0), 0u) << estimate.warnings[0];
}

TEST(FlightFeed, TakesTheSignalsTheNodeSubscribesTo) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  pe::FlightStreams streams = steadyCommand(1500.0, 11.5, 2.0);
  streams.input(pe::input::Scalar::kAirTemperature).push_back({0.5, -100.0});  // outside -60..85 deg C
  // Without an effect that reads it the node does not subscribe to the air temperature: not refused.
  const pe::PropulsionModel plain = thesisModel();
  pe::OnboardSession session(plain, vehicle, pe::offline::replayOnboardConfig(vehicle));
  const pe::offline::FlightFeed feed(streams);
  for (const pe::offline::Arrival& a : feed.arrivals()) feed.feed(a, &session);
  const pe::Estimator& estimator = session.estimator();
  EXPECT_EQ(estimator.counters().rejected[static_cast<int>(pe::Rejection::kBadInput)], 0u);
  EXPECT_EQ(estimator.counters().accepted, streams.rc_out.size());
  // Arrivals by time, the inputs before the RCOut message they feed.
  ASSERT_EQ(feed.arrivals().front().kind, pe::offline::Stream::kBattery);
  for (std::size_t i = 1; i < feed.arrivals().size(); ++i) {
    EXPECT_LE(feed.arrivals()[i - 1].time_s, feed.arrivals()[i].time_s);
  }
}

TEST(FlightFeed, FeedsTheAirTemperatureToAModelThatReadsIt) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  pe::FlightStreams streams = steadyCommand(1500.0, 11.5, 2.0);
  streams.input(pe::input::Scalar::kAirTemperature).push_back({0.5, -100.0});
  pe::effects::ModelEffects fx = thesisModel().effects();
  fx.air_reference_density_kg_m3 = 1.2;
  fx.setParameter(pe::effects::Kind::kAirDensity, 1.0);
  const pe::PropulsionModel model = thesisModel().withEffects(fx);
  pe::OnboardSession session(model, vehicle, pe::offline::replayOnboardConfig(vehicle));
  const pe::offline::FlightFeed feed(streams);
  for (const pe::offline::Arrival& a : feed.arrivals()) feed.feed(a, &session);
  EXPECT_EQ(session.estimator().counters().rejected[static_cast<int>(pe::Rejection::kBadInput)], 1u);
  EXPECT_EQ(session.estimator().counters().rejected_inputs[pe::input::index(pe::input::Scalar::kAirTemperature)], 1u);
}

// A log keeps a rangefinder's valid readings only (its sensor's limits are not logged): each is
// taken, +inf (nothing within reach) included, and the ground effect applied. Fed as a
// sensor_msgs/Range without limits they were all refused before the inputs had one entry each.
TEST(FlightFeed, TakesALoggedRangeAsValid) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  pe::FlightStreams streams = steadyCommand(1500.0, 11.5, 2.0);
  auto& range = streams.input(pe::input::Scalar::kRangefinder);
  for (double t = 0.0; t < 2.0; t += 0.05) range.push_back({t, t < 1.0 ? 0.3 : std::numeric_limits<double>::infinity()});
  pe::effects::ModelEffects fx = thesisModel().effects();
  fx.setParameter(pe::effects::Kind::kGroundEffect, 0.0011);
  const pe::PropulsionModel model = thesisModel().withEffects(fx);
  pe::OnboardSession session(model, vehicle, pe::offline::replayOnboardConfig(vehicle));
  ASSERT_TRUE(session.readsInput(pe::input::Scalar::kRangefinder));
  const pe::offline::FlightFeed feed(streams);
  for (const pe::offline::Arrival& a : feed.arrivals()) feed.feed(a, &session);
  const pe::EstimatorCounters& counters = session.estimator().counters();
  EXPECT_EQ(counters.rejected[static_cast<int>(pe::Rejection::kBadInput)], 0u);
  EXPECT_GT(counters.effect_applied[static_cast<int>(pe::effects::Kind::kGroundEffect)], 0u);
  EXPECT_EQ(counters.effect_skipped[static_cast<int>(pe::effects::Kind::kGroundEffect)], 0u);
}

TEST(EstimateOptions, RefusesASampleRateOutsideItsRange) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  pe::offline::EstimateOptions options = optionsFor(vehicle);
  options.sample_rate_hz = -1.0;
  try {
    options.validate(4);
    FAIL() << "accepted";
  } catch (const pe::FieldError& e) {
    EXPECT_STREQ(e.what(), "sample_rate_hz: -1 is outside 0..1000 Hz");
  }
}

TEST(EstimateCsv, RoundTripsEverySampleWithNaNAsAnEmptyCell) {
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  pe::offline::EstimateOptions options = optionsFor(vehicle);
  options.sample_rate_hz = 0.0;
  const pe::offline::FlightEstimate estimate =
      pe::offline::estimateFlight(thesisModel(), vehicle, shortFlight(), options);
  const std::string text = pe::offline::estimateCsv(estimate.samples);
  const std::vector<pe::offline::EstimateSample> read = pe::offline::parseEstimateCsv(text, "estimates.csv");
  ASSERT_EQ(read.size(), estimate.samples.size());
  std::size_t nan_totals = 0;
  for (std::size_t i = 0; i < read.size(); ++i) {
    const auto& a = estimate.samples[i];
    const auto& b = read[i];
    EXPECT_NEAR(b.time_s, a.time_s, 1e-9 * std::fabs(a.time_s) + 1e-12);
    EXPECT_NEAR(b.lifted_mass_kg, a.lifted_mass_kg, 1e-8);
    EXPECT_EQ(b.hovering, a.hovering);
    EXPECT_EQ(std::isnan(b.total_mass_kg), std::isnan(a.total_mass_kg));
    nan_totals += std::isnan(b.total_mass_kg);
    if (!std::isnan(a.total_mass_kg)) {
      EXPECT_NEAR(b.total_mass_kg, a.total_mass_kg, 1e-8);
    }
    EXPECT_EQ(b.motors_out_of_domain, a.motors_out_of_domain);
    ASSERT_EQ(b.motor_thrust_n.size(), 4u);
    EXPECT_NEAR(b.motor_thrust_n[2], a.motor_thrust_n[2], 1e-8);
  }
  EXPECT_GT(nan_totals, 0u);  // before the first hover
  EXPECT_EQ(pe::offline::estimateCsv(read), text);
}

TEST(EstimateCsv, RefusesAMissingColumnAndACellThatIsNoNumber) {
  try {
    pe::offline::parseEstimateCsv("time_s,voltage_v\n1,2\n", "e.csv");
    FAIL() << "accepted";
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "e.csv:1: column 3 should be 'thrust_n', it is missing");
  }
  const std::string header =
      "time_s,voltage_v,thrust_n,current_a,power_w,lifted_mass_kg,hovering,total_mass_kg,mass_std_kg,payload_kg,"
      "motors_out_of_domain,thrust_1_n\n";
  try {
    pe::offline::parseEstimateCsv(header + "1,12,10,5,60,1.0,1,1.0,0.01,0.1,0,abc\n", "e.csv");
    FAIL() << "accepted";
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "e.csv:2: column 12 'thrust_1_n': 'abc' is not a number");
  }
}

TEST(EstimateSummary, ListsTheHoversAndTheWarnings) {
  const pe::Vehicle vehicle = pe::Vehicle::upwardRotors(4);
  const pe::offline::FlightEstimate estimate =
      pe::offline::estimateFlight(thesisModel(), vehicle, steadyCommand(1500.0, 15.1, 20.0), optionsFor(vehicle));
  const std::string text = pe::offline::estimateSummaryMarkdown(estimate, "model.yaml", "mass.png");
  EXPECT_NE(text.find("# Estimate of steady.ulg"), std::string::npos);
  EXPECT_NE(text.find("![mass and payload over time](mass.png)"), std::string::npos);
  EXPECT_NE(text.find("| 1 | "), std::string::npos);
  EXPECT_NE(text.find("- 100.0 % of the motor samples lie outside"), std::string::npos);
  EXPECT_NE(text.find("Empty mass: n/a (none)"), std::string::npos);
}

namespace {

std::string writeParams(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(YamlParameterSource, TheNodesTemplateReadsAsTheNodesDefaults) {
  const pe::offline::YamlParameterSource source(repoPath("config/estimator_params.yaml"), {{"model", "m.yaml"}});
  const pe::EstimatorNodeParams read = pe::readNodeParameters(source);
  const pe::EstimatorNodeParams defaults;
  EXPECT_EQ(read.model, "m.yaml");
  EXPECT_EQ(read.estimator.motor_channels, defaults.estimator.motor_channels);
  EXPECT_EQ(read.estimator.hover.window_s, defaults.estimator.hover.window_s);
  EXPECT_EQ(read.estimator.hover.min_mass_kg, defaults.estimator.hover.min_mass_kg);
  EXPECT_EQ(read.estimator.payload.min_samples, defaults.estimator.payload.min_samples);
  EXPECT_EQ(read.estimator.compensate_tilt, defaults.estimator.compensate_tilt);
  EXPECT_EQ(read.capability.min_thrust_to_weight, defaults.capability.min_thrust_to_weight);
  EXPECT_EQ(read.capability.motor_health.window_s, defaults.capability.motor_health.window_s);
  EXPECT_EQ(read.esc_telemetry.rpm_tolerance, defaults.esc_telemetry.rpm_tolerance);
  EXPECT_EQ(read.publish_rate_hz, defaults.publish_rate_hz);
}

TEST(YamlParameterSource, ReadsNestedKeysAsTheLaunchFileLoadsThem) {
  const std::string path = writeParams("pe_params_nested.yaml", "hover:\n  min_mass_kg: 0.01\npayload: {min_samples: 10}\n");
  const pe::EstimatorNodeParams read =
      pe::readNodeParameters(pe::offline::YamlParameterSource(path, {{"model", "m.yaml"}}));
  EXPECT_EQ(read.estimator.hover.min_mass_kg, 0.01);
  EXPECT_EQ(read.estimator.payload.min_samples, 10u);
}

TEST(YamlParameterSource, RefusesAWrongTypeAnUnknownNameAndAMissingModelNamingFileAndKey) {
  const auto refusal = [](const std::string& text, const std::map<std::string, std::string>& set) {
    const std::string path = writeParams("pe_params_bad.yaml", text);
    try {
      pe::readNodeParameters(pe::offline::YamlParameterSource(path, set));
    } catch (const pe::ConfigError& e) {
      return std::string(e.what()).substr(path.size());
    }
    return std::string("accepted");
  };
  const std::map<std::string, std::string> model{{"model", "m.yaml"}};
  EXPECT_EQ(refusal("hover: {window_s: two}\n", model), ": hover/window_s: wrong type, expected a number");
  EXPECT_EQ(refusal("hover: {windw_s: 2}\n", model),
            ": hover/windw_s: unknown parameter (see the README's parameter table)");
  EXPECT_EQ(refusal("hover: {window_s: 2}\n", {}), ": model: required parameter is not set");
  EXPECT_EQ(refusal("[1, 2]\n", model), ": expected a mapping of parameters");
}

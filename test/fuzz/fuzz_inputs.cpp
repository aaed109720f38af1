#include "fuzz_inputs.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <ros/serialization.h>
#include <topic_tools/shape_shifter.h>

#include "propulsion_estimator/bag/flight_bag_reader.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/onboard/pack_learner.h"
#include "propulsion_estimator/onboard/tare_file.h"
#include "propulsion_estimator/logs/bench_csv.h"
#include "propulsion_estimator/logs/csv_text.h"
#include "propulsion_estimator/logs/dataflash_flight_reader.h"
#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/logs/tyto_csv.h"
#include "propulsion_estimator/logs/ulog_flight_reader.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/codecs/rcout_codec.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"

namespace propulsion_estimator {
namespace fuzz {
namespace {

/// Runs `read` on the input as text: true when it returns, false when it refuses with InputError.
template <typename Read>
bool acceptsText(const std::uint8_t* data, std::size_t size, Read read) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    read(text);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

bool feedModelYaml(const std::uint8_t* data, std::size_t size) {
  return acceptsText(data, size, [](const std::string& text) { parseModelYaml(text, "fuzz.yaml"); });
}

bool feedBenchCsv(const std::uint8_t* data, std::size_t size) {
  return acceptsText(data, size, [](const std::string& text) { parseNativeBenchCsv(text, "fuzz.csv"); });
}

// Read twice: with the automatic choices, and with the user's overrides (sign kept or negated, a
// decimal comma imposed), which take other paths through the reader. Accepted means with the first.
bool feedTytoCsv(const std::uint8_t* data, std::size_t size) {
  const bool accepted = acceptsText(data, size, [](const std::string& text) {
    tytoBenchLogFromTable(splitCsvText(text, "fuzz.csv"), BenchReadOptions{});
  });
  acceptsText(data, size, [](const std::string& text) {
    BenchReadOptions imposed;
    imposed.thrust_sign = SignPolicy::kNegate;
    imposed.current_sign = SignPolicy::kAsLogged;
    imposed.decimal = DecimalSeparator::kComma;
    tytoBenchLogFromTable(splitCsvText(text, "fuzz.csv"), imposed);
  });
  return accepted;
}

bool feedFlightManifest(const std::uint8_t* data, std::size_t size) {
  return acceptsText(data, size, [](const std::string& text) { parseFlightManifest(text, "fuzz.manifest.yaml"); });
}

bool feedFlightProfile(const std::uint8_t* data, std::size_t size) {
  return acceptsText(data, size, [](const std::string& text) { sim::parseFlightProfileYaml(text, "fuzz_flight.yaml"); });
}

bool feedVehicleUrdf(const std::uint8_t* data, std::size_t size) {
  return acceptsText(data, size, [](const std::string& text) { vehicleFromUrdf(text, "fuzz.urdf"); });
}

bool feedTareFile(const std::uint8_t* data, std::size_t size) {
  return acceptsText(data, size, [](const std::string& text) { parseTareFile(text, "fuzz_tare.yaml"); });
}

// A pack file read back, and the curve the node would build from it (learnedCurve: every table a
// file can hold must give a curve or be refused by the reader).
bool feedPackFile(const std::uint8_t* data, std::size_t size) {
  return acceptsText(data, size, [](const std::string& text) {
    learnedCurve(parsePackFile(text, "fuzz_pack.yaml"), OcvCurve::lipo());
  });
}

// The bytes as the serialized payload of a mavros_msgs/RCOut, received as the node receives it
// (a ShapeShifter read from the wire) and as a bag reader hands it over (decodePayload). The
// decoder refuses by returning false with a reason instead of throwing.
bool feedRcOut(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  topic_tools::ShapeShifter shifter;
  shifter.morph(kRcOutMd5Sum, kRcOutDataType, rcOutDefinition(), "0");
  // roscpp reads an empty message into a ShapeShifter by a memcpy to a null pointer (its header's
  // undefined behaviour, not this package's): the ShapeShifter as it is reads the same as empty.
  if (!bytes.empty()) {
    ros::serialization::IStream reader(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    shifter.read(reader);
  }
  RcOutDecoder decoder;
  RcOutMessage message;
  std::string error;
  const bool decoded = decoder.decode(shifter, &message, &error);
  if (decoded != error.empty()) throw std::logic_error("RcOutDecoder::decode: result and reason disagree");
  RcOutMessage direct;
  std::string direct_error;
  const bool direct_decoded =
      RcOutDecoder::decodePayload(bytes.data(), static_cast<std::uint32_t>(bytes.size()), &direct, &direct_error);
  if (direct_decoded != decoded || direct_error != error)
    throw std::logic_error("RcOutDecoder::decode and decodePayload disagree: '" + error + "', '" + direct_error + "'");
  if (decoded && (message.channels != direct.channels || message.header.frame_id != direct.header.frame_id))
    throw std::logic_error("RcOutDecoder::decode and decodePayload decoded differently");
  return decoded;
}

// A flight log read as diagnose_gap reads it; a log read up to a damaged message must say where,
// in one line.
template <typename Reader>
bool feedFlightLog(const std::uint8_t* data, std::size_t size, const char* path) {
  return acceptsText(data, size, [path](const std::string& bytes) {
    const Reader reader(bytes, path);
    FlightLogOptions options;
    options.motors = 4;
    options.pwm_min_us = 1000.0;
    options.pwm_max_us = 2000.0;
    const std::string refusal = reader.refusal();
    if (!refusal.empty() && (refusal.rfind(std::string(path) + ": at byte ", 0) != 0 ||
                             refusal.find('\n') != std::string::npos)) {
      throw std::logic_error("a refusal not of one line naming the file and the byte: " + refusal);
    }
    const FlightStreams streams = reader.read(options);
    if (streams.rc_out.empty() || streams.battery.empty()) throw std::logic_error("read without rc_out or battery");
  });
}

bool feedUlog(const std::uint8_t* data, std::size_t size) {
  return feedFlightLog<UlogFlightReader>(data, size, "fuzz.ulg");
}

bool feedDataflash(const std::uint8_t* data, std::size_t size) {
  return feedFlightLog<DataflashFlightReader>(data, size, "fuzz.bin");
}

// A rosbag as diagnose_gap reads it. rosbag opens files only: the input goes to a file of this
// process first.
bool feedFlightBag(const std::uint8_t* data, std::size_t size) {
  // The file is removed as the process ends: a run per process id would otherwise leave one behind.
  struct RemovedAtExit {
    std::string path;
    ~RemovedAtExit() {
      std::error_code error;
      std::filesystem::remove(path, error);
    }
  };
  static const RemovedAtExit file{
      (std::filesystem::temp_directory_path() / ("pe_fuzz_" + std::to_string(::getpid()) + ".bag")).string()};
  const std::string& path = file.path;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);
  try {
    const FlightBagReader reader(path);
    FlightLogOptions options;
    options.motors = 4;
    const FlightStreams streams = reader.read(options);
    if (streams.rc_out.empty() || streams.battery.empty()) throw std::logic_error("read without rc_out or battery");
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

const std::vector<FuzzInput>& fuzzInputs() {
  static const std::vector<FuzzInput> inputs = {
      {"model_yaml", feedModelYaml},           {"bench_csv", feedBenchCsv},
      {"tyto_csv", feedTytoCsv},               {"flight_manifest", feedFlightManifest},
      {"flight_profile", feedFlightProfile},   {"vehicle_urdf", feedVehicleUrdf},
      {"rcout", feedRcOut},                    {"tare_file", feedTareFile},
      {"pack_file", feedPackFile},             {"ulog", feedUlog},
      {"dataflash", feedDataflash},            {"flight_bag", feedFlightBag},
  };
  return inputs;
}

const FuzzInput& fuzzInput(const std::string& name) {
  std::string names;
  for (const FuzzInput& input : fuzzInputs()) {
    if (name == input.name) return input;
    names += std::string(names.empty() ? "" : ", ") + input.name;
  }
  throw std::invalid_argument("no fuzzed reader '" + name + "' (known: " + names + ")");
}

}  // namespace fuzz
}  // namespace propulsion_estimator

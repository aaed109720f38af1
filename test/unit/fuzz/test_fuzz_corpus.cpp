// The fuzzers' corpora and the inputs that were findings, replayed through the same entry points
// (test/fuzz/fuzz_inputs.h) in every `make test`: each input is accepted or refused with
// InputError, nothing else. The fuzzing itself is `make fuzz`.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz_inputs.h"
#include "test_paths.h"

namespace fs = std::filesystem;
namespace fuzz = propulsion_estimator::fuzz;

namespace {

std::vector<fs::path> filesIn(const fs::path& folder) {
  std::vector<fs::path> files;
  if (!fs::is_directory(folder)) return files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string contentOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct Outcome {
  int accepted = 0;
  int refused = 0;
};

Outcome replay(const fuzz::FuzzInput& input, const fs::path& folder) {
  Outcome outcome;
  for (const fs::path& file : filesIn(folder)) {
    const std::string bytes = contentOf(file);
    try {
      (input.feed(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()) ? outcome.accepted
                                                                                      : outcome.refused)++;
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": neither accepted nor refused with InputError: " << e.what();
    }
  }
  return outcome;
}

}  // namespace

// The corpus folders are the list of fuzzed inputs (CMake and scripts/run_fuzzers.sh read them):
// each names an entry point, and each entry point has one.
TEST(FuzzCorpus, TheCorpusFoldersAreTheEntryPoints) {
  std::vector<std::string> folders, inputs;
  for (const fs::directory_entry& entry : fs::directory_iterator(repoPath("test/fuzz/corpus"))) {
    if (entry.is_directory()) folders.push_back(entry.path().filename().string());
  }
  for (const fuzz::FuzzInput& input : fuzz::fuzzInputs()) inputs.push_back(input.name);
  std::sort(folders.begin(), folders.end());
  std::sort(inputs.begin(), inputs.end());
  EXPECT_EQ(folders, inputs);
}

TEST(FuzzCorpus, EveryReaderHasASeedCorpusThatItAcceptsInPart) {
  for (const fuzz::FuzzInput& input : fuzz::fuzzInputs()) {
    const Outcome outcome = replay(input, repoPath("test/fuzz/corpus/") + input.name);
    EXPECT_GT(outcome.accepted, 0) << input.name << ": no valid example in its corpus";
    EXPECT_LE(outcome.accepted + outcome.refused, 64) << input.name << ": corpus grown beyond a few dozen files";
  }
}

// Each finding is accepted or refused; the damaged bags that crashed rosbag or made it allocate
// gigabytes are all refused, none read as a flight.
TEST(FuzzCorpus, EveryFindingIsNowAcceptedOrRefused) {
  for (const fuzz::FuzzInput& input : fuzz::fuzzInputs()) {
    const std::string folder = repoPath("test/fuzz/regressions/") + input.name;
    const Outcome outcome = replay(input, folder);
    if (input.name != std::string("flight_bag")) continue;
    EXPECT_EQ(outcome.accepted, 0);
    EXPECT_EQ(outcome.refused, static_cast<int>(filesIn(folder).size()));
    EXPECT_GE(outcome.refused, 7);
  }
}

TEST(FuzzCorpus, UnknownReaderIsNamedWithTheKnownOnes) {
  try {
    fuzz::fuzzInput("nope");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "no fuzzed reader 'nope' (known: model_yaml, bench_csv, tyto_csv, flight_manifest, flight_profile, "
              "vehicle_urdf, rcout, tare_file, pack_file, ulog, dataflash, flight_bag)");
  }
}

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/atomic_file.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/estimation/payload_estimator.h"
#include "propulsion_estimator/onboard/tare_file.h"

namespace pe = propulsion_estimator;

TEST(PayloadEstimator, AveragesHoverSamplesOnly) {
  pe::PayloadConfig config;
  config.min_samples = 4;
  pe::PayloadEstimator estimator(config);
  estimator.setEmptyMass(1.3, pe::EmptyMassSource::kParameter);
  estimator.add(0.0, 9.0, false);  // a climb: not averaged
  for (int k = 1; k <= 3; ++k) estimator.add(k * 0.02, 1.6, true);
  EXPECT_EQ(estimator.estimate().state, pe::PayloadState::kWaitingForHover);
  estimator.add(0.08, 1.8, true);
  const pe::MassEstimate& e = estimator.estimate();
  EXPECT_EQ(e.state, pe::PayloadState::kHovering);
  EXPECT_NEAR(e.total_mass_kg, 1.65, 1e-12);
  EXPECT_NEAR(e.mass_std_kg, 0.1, 1e-12);  // sample standard deviation of 1.6, 1.6, 1.6, 1.8
  EXPECT_NEAR(e.payload_mass_kg, 0.35, 1e-12);
  EXPECT_EQ(e.window_samples, 4u);
  EXPECT_NEAR(e.window_s, 0.06, 1e-12);
  estimator.add(0.1, 5.0, false);
  EXPECT_EQ(estimator.estimate().state, pe::PayloadState::kHolding);
  EXPECT_NEAR(estimator.estimate().total_mass_kg, 1.65, 1e-12);
}

TEST(PayloadEstimator, APauseInHoverStartsANewEpisode) {
  pe::PayloadConfig config;
  config.min_samples = 2;
  pe::PayloadEstimator estimator(config);
  estimator.add(0.0, 1.3, true);
  estimator.add(0.1, 1.3, true);
  estimator.add(2.0, 1.7, false);  // winched a payload up between hovers
  estimator.add(3.0, 1.7, true);
  estimator.add(3.1, 1.7, true);
  EXPECT_NEAR(estimator.estimate().total_mass_kg, 1.7, 1e-12);
  EXPECT_EQ(estimator.estimate().window_samples, 2u);
}

TEST(PayloadConfig, RefusesNonsense) {
  pe::PayloadConfig config;
  config.min_samples = 1;
  try {
    config.validate();
    FAIL();
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "payload/min_samples: must be at least 2, got 1");
  }
}

TEST(TareFile, RoundTripsAndRefusesGarbage) {
  const std::string path = testing::TempDir() + "/pe_tare/tare.yaml";
  pe::removeTareFile(path);
  EXPECT_FALSE(pe::loadTareFile(path).has_value());
  pe::saveTareFile(path, {1.2983456789012345, "/models/with \"quotes\".yaml", "0123456789abcdef"});
  const auto record = pe::loadTareFile(path);
  ASSERT_TRUE(record.has_value());
  EXPECT_EQ(record->empty_mass_kg, 1.2983456789012345);
  EXPECT_EQ(record->model, "/models/with \"quotes\".yaml");
  EXPECT_EQ(record->model_fingerprint, "0123456789abcdef");
  {
    std::ofstream out(path);
    out << "empty_mass_kg: heavy\nmodel: m.yaml\nmodel_fingerprint: 0123456789abcdef\n";
  }
  try {
    pe::loadTareFile(path);
    FAIL();
  } catch (const pe::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":1: empty_mass_kg: expected a number, got 'heavy'");
  }
  // Whether a file was removed (~reset's answer says so).
  EXPECT_TRUE(pe::removeTareFile(path));
  EXPECT_FALSE(pe::removeTareFile(path));
}

namespace {

// The message of the InputError `action` throws, or "no error".
template <typename Action>
std::string inputError(Action action) {
  try {
    action();
  } catch (const pe::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(TareFile, RefusesAnEmptyFileAndDuplicateKeys) {
  const std::string folder = testing::TempDir() + "/pe_tare_refused";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string path = folder + "/tare.yaml";
  std::ofstream(path).close();
  EXPECT_EQ(inputError([&] { pe::loadTareFile(path); }), path + ": the file is empty");
  std::ofstream(path) << "empty_mass_kg: 1.2\nmodel: m.yaml\nempty_mass_kg: 1.5\nmodel_fingerprint: 0123\n";
  EXPECT_EQ(inputError([&] { pe::loadTareFile(path); }),
            path + ":3: empty_mass_kg: key given twice (first on line 1)");
  std::filesystem::remove_all(folder);
}

// At a node's start: none, a tare, content that is not one (moved aside for the next ~tare), and a
// folder named as the file (the user's: left where it is).
TEST(TareFile, AtStartMovesRefusedContentAsideAndLeavesWhatCannotBeRead) {
  const std::string folder = testing::TempDir() + "/pe_tare_at_start";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string path = folder + "/tare.yaml";
  pe::TareAtStart none = pe::loadTareAtStart(path, 1700000000);
  EXPECT_FALSE(none.record.has_value());
  EXPECT_EQ(none.refusal, "");
  pe::saveTareFile(path, {1.25, "m.yaml", "0123"});
  const pe::TareAtStart tare = pe::loadTareAtStart(path, 1700000000);
  ASSERT_TRUE(tare.record.has_value());
  EXPECT_EQ(tare.record->empty_mass_kg, 1.25);
  EXPECT_EQ(tare.refusal, "");
  std::ofstream(path) << "empty_mass_kg: heavy\nmodel: m.yaml\nmodel_fingerprint: 0123\n";
  const pe::TareAtStart refused = pe::loadTareAtStart(path, 1700000000);
  EXPECT_FALSE(refused.record.has_value());
  EXPECT_EQ(refused.refusal, "refused: " + path + ":1: empty_mass_kg: expected a number, got 'heavy'; started without "
                             "the tare, the file moved to " + path + ".bad-1700000000");
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_TRUE(std::filesystem::exists(path + ".bad-1700000000"));
  std::filesystem::create_directories(path);
  const pe::TareAtStart unreadable = pe::loadTareAtStart(path, 1700000001);
  EXPECT_EQ(unreadable.refusal, "refused: " + path + ": a folder, not a file; started without the tare");
  EXPECT_TRUE(std::filesystem::is_directory(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".bad-1700000001"));
  std::filesystem::remove_all(folder);
}

TEST(TareFile, WritesThroughAUniqueTemporaryFileAndLeavesNoneBehind) {
  const std::string folder = testing::TempDir() + "/pe_tare_unique";
  std::filesystem::remove_all(folder);
  const std::string path = folder + "/tare.yaml";
  // A temporary file of the old fixed name (another node's, mid-write) is neither used nor touched.
  std::filesystem::create_directories(folder);
  std::ofstream(path + ".tmp") << "another node's half-written tare";
  pe::saveTareFile(path, {1.25, "m.yaml", "0123"});
  pe::saveTareFile(path, {1.5, "m.yaml", "0123"});
  EXPECT_EQ(pe::loadTareFile(path)->empty_mass_kg, 1.5);
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"tare.yaml", "tare.yaml.tmp"}));
  std::filesystem::remove_all(folder);
}

TEST(TareFile, SaysWhenItCannotBeWrittenRemovedOrMovedAside) {
  const std::string folder = testing::TempDir() + "/pe_tare_failures";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  // A regular file where the tare file's folder should be.
  std::ofstream(folder + "/file").close();
  const std::string under_file = folder + "/file/tare.yaml";
  EXPECT_EQ(inputError([&] { pe::saveTareFile(under_file, {1.25, "m.yaml", "0123"}); }),
            under_file + ": tare file not written: cannot create a temporary file next to it: Not a directory");
  // A non-empty folder where the tare file should be: neither replaced nor removed; no temporary file left.
  const std::string folder_in_the_way = folder + "/tare.yaml";
  std::filesystem::create_directories(folder_in_the_way + "/inside");
  EXPECT_EQ(inputError([&] { pe::saveTareFile(folder_in_the_way, {1.25, "m.yaml", "0123"}); }),
            folder_in_the_way + ": tare file not written: cannot replace it with the temporary file: Is a directory");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()), 2);
  EXPECT_EQ(inputError([&] { pe::removeTareFile(folder_in_the_way); }),
            folder_in_the_way + ": cannot remove the tare file: Directory not empty");
  EXPECT_EQ(inputError([&] { pe::removeTareFile(folder + "/absent.yaml"); }), "no error");
  EXPECT_EQ(inputError([&] { pe::setAsideTareFile(folder + "/absent.yaml", 1700000000); }),
            folder + "/absent.yaml: cannot move the tare file to " + folder +
                "/absent.yaml.bad-1700000000: No such file or directory");
  std::filesystem::remove_all(folder);
}

// A node killed while ~tare wrote leaves its temporary file: the next start removes it once stale.
TEST(TareFile, RemovesOnlyStaleTemporariesOfItsOwnFile) {
  namespace fs = std::filesystem;
  const std::string folder = testing::TempDir() + "/pe_tare_stale";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string path = folder + "/tare.yaml";
  const auto age = [](const std::string& file, double seconds) {
    fs::last_write_time(file, fs::file_time_type::clock::now() -
                                  std::chrono::duration_cast<fs::file_time_type::duration>(
                                      std::chrono::duration<double>(seconds)));
  };
  std::ofstream(path) << "empty_mass_kg: 1.25\nmodel: m.yaml\nmodel_fingerprint: '0123'\n";
  std::ofstream(path + ".tmp-4242-0-77") << "killed mid-write";
  std::ofstream(path + ".tmp-4343-0-77") << "being written now";
  std::ofstream(folder + "/other.yaml.tmp-4242-0-77") << "another file's";
  age(path, 3600.0);
  age(path + ".tmp-4242-0-77", pe::kStaleTemporaryAgeS + 5.0);
  age(folder + "/other.yaml.tmp-4242-0-77", 3600.0);
  EXPECT_EQ(pe::removeStaleTareTemporaries(path), (std::vector<std::string>{path + ".tmp-4242-0-77"}));
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"other.yaml.tmp-4242-0-77", "tare.yaml", "tare.yaml.tmp-4343-0-77"}));
  // No folder (a tare file not yet written anywhere): nothing to remove, no error.
  EXPECT_TRUE(pe::removeStaleTareTemporaries(folder + "/absent/tare.yaml").empty());
  fs::remove_all(folder);
}

TEST(TareFile, MovesABadFileAside) {
  const std::string folder = testing::TempDir() + "/pe_tare_aside";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string path = folder + "/tare.yaml";
  std::ofstream(path) << "garbage";
  EXPECT_EQ(pe::setAsideTareFile(path, 1700000000), path + ".bad-1700000000");
  EXPECT_FALSE(std::filesystem::exists(path));
  std::ifstream aside(path + ".bad-1700000000");
  std::string text;
  std::getline(aside, text);
  EXPECT_EQ(text, "garbage");
  EXPECT_FALSE(pe::loadTareFile(path).has_value());
  std::filesystem::remove_all(folder);
}

// Reading a whole file: a folder named as a file is refused by name; a file required as a file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/text_file.h"

namespace pe = propulsion_estimator;

// A folder opens as a stream whose size reads as the largest offset: it once ended in
// "basic_string::_M_create", naming neither the file nor the parameter.
TEST(TextFile, RefusesAFolderByName) {
  const std::string folder = testing::TempDir() + "/pe_text_file_folder";
  std::filesystem::create_directories(folder);
  try {
    pe::readTextFile(folder);
    ADD_FAILURE() << "a folder was read";
  } catch (const pe::InputError& e) {
    EXPECT_EQ(std::string(e.what()), folder + ": a folder, not a file");
  }
  std::filesystem::remove_all(folder);
  pe::writeTextFile(folder, "text\n");
  EXPECT_EQ(pe::readTextFile(folder), "text\n");
  std::filesystem::remove(folder);
}

// A log named by the user must be a file: a folder, a device and a missing path are each said as
// what they are (a folder and /dev/null were both "no such file").
TEST(TextFile, RequiresARegularFileSayingWhatItIsInstead) {
  const auto refusal = [](const std::string& path) {
    try {
      pe::requireRegularFile(path);
    } catch (const pe::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string folder = testing::TempDir() + "/pe_regular_file";
  std::filesystem::create_directories(folder);
  EXPECT_EQ(refusal(folder), folder + ": a folder, not a file");
  EXPECT_EQ(refusal("/dev/null"), "/dev/null: not a regular file (a device, pipe or socket)");
  EXPECT_EQ(refusal(folder + "/none.ulg"), folder + "/none.ulg: no such file");
  pe::writeTextFile(folder + "/a.ulg", "x");
  EXPECT_EQ(refusal(folder + "/a.ulg"), "accepted");
  std::filesystem::remove_all(folder);
}

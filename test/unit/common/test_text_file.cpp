// Reading a whole file: a folder named as a file is refused by name.
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

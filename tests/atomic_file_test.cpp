#include "sim/util/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "sim/util/input_error.h"

namespace gyrotherm::sim {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gyrotherm_atomic_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::size_t files_in_dir() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}));
  }
  fs::path dir_;
};

TEST_F(AtomicFileTest, CommitReplacesTheTarget) {
  const fs::path target = dir_ / "out.csv";
  write_file_atomically(target, "old\n");
  write_file_atomically(target, "new\n");
  EXPECT_EQ(slurp(target), "new\n");
  EXPECT_EQ(files_in_dir(), 1u);  // no temporaries left
}

TEST_F(AtomicFileTest, AFailureHalfwayLeavesThePreviousResultIntact) {
  const fs::path target = dir_ / "out.csv";
  write_file_atomically(target, "previous result\n");
  try {
    AtomicFile file(target);
    file.stream() << "half a new res";
    throw std::runtime_error("interrupted");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(slurp(target), "previous result\n");
  EXPECT_EQ(files_in_dir(), 1u);
}

TEST_F(AtomicFileTest, MissingFolderIsAnInputErrorNamingTheFile) {
  const fs::path target = dir_ / "no" / "such" / "out.csv";
  try {
    AtomicFile file(target);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos);
  }
}

TEST_F(AtomicFileTest, ADeviceOrAFolderIsNeverReplaced) {
  // Renaming over /dev/null as root would turn the device into a file.
  for (const fs::path& target : {fs::path("/dev/null"), dir_}) {
    try {
      AtomicFile file(target);
      FAIL() << target;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(files_in_dir(), 0u);
}

}  // namespace
}  // namespace gyrotherm::sim

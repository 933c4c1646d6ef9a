// Where installed programs find their data: beside their bin folder.
#include "common/data_dir.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

TEST(DataDir, IsShareMrsimBesideTheProgramsFolder) {
  unsetenv("MRSIM_DATA_DIR");
  const fs::path prefix = testing::TempDir("data_dir_prefix");
  fs::create_directories(prefix / "bin");
  const std::string program = (prefix / "bin" / "mrsim-sim").string();
  EXPECT_EQ(DataDirFor(program), "") << "no share/mrsim yet";
  fs::create_directories(prefix / "share" / "mrsim");
  EXPECT_EQ(DataDirFor(program), (prefix / "share" / "mrsim").string());
}

TEST(DataDir, EnvironmentVariableWins) {
  setenv("MRSIM_DATA_DIR", "/somewhere/else", 1);
  EXPECT_EQ(DataDirFor("/usr/bin/mrsim"), "/somewhere/else");
  unsetenv("MRSIM_DATA_DIR");
}

TEST(DataDir, BuildTreeHasNoneSoProgramsKeepSourceTreePaths) {
  unsetenv("MRSIM_DATA_DIR");
  // The test binary lives in build/tests/common_lib: no ../share/mrsim.
  EXPECT_EQ(DataDir(), "");
  EXPECT_EQ(FindDataFile("scenarios/case_study.xml"), "");
}

}  // namespace
}  // namespace mrsim

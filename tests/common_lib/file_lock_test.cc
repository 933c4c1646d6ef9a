// One writer per folder (common/file_lock.h).
#include "common/file_lock.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

std::string Contents(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(FileLock, ASecondHolderIsRefusedWithTheFirstOnesPid) {
  const std::string path = testing::TempDir("file_lock_busy") + "/run.lock";
  {
    FileLock first(path);
    EXPECT_EQ(Contents(path), std::to_string(getpid()) + "\n");
    try {
      FileLock second(path);
      FAIL() << "two holders";
    } catch (const FileLockBusy& e) {
      EXPECT_EQ(e.holder(), getpid());
      EXPECT_NE(std::string(e.what()).find("is locked by process " +
                                           std::to_string(getpid())),
                std::string::npos)
          << e.what();
    }
  }
  // Released: free again, and not stale.
  FileLock again(path);
  EXPECT_EQ(again.stale_holder(), 0);
}

// A run killed with the lock leaves its pid in the file but no lock (the
// kernel drops it with the process): the next run takes it over.
TEST(FileLock, AStaleLockIsTakenOver) {
  const std::string path = testing::TempDir("file_lock_stale") + "/run.lock";
  std::ofstream(path) << "4242\n";
  FileLock lock(path);
  EXPECT_EQ(lock.stale_holder(), 4242);
  EXPECT_EQ(Contents(path), std::to_string(getpid()) + "\n");
}

TEST(FileLock, AnUnopenableFileIsNamed) {
  try {
    FileLock lock("/nonexistent-dir/run.lock");
    FAIL();
  } catch (const FileLockBusy&) {
    FAIL() << "not busy";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/run.lock"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace mrsim

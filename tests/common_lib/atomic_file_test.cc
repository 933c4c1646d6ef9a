#include "common/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, WritesEveryByteAndLeavesNoTemporary) {
  const std::string dir = testing::TempDir("atomic_write");
  const std::string path = dir + "/a.bin";
  std::string bytes(100000, '\0');
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i);
  WriteFileAtomically(path, bytes);
  EXPECT_EQ(ReadAll(path), bytes);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(AtomicFile, ReplacesTheOldContent) {
  const std::string path = testing::TempDir("atomic_replace") + "/a.txt";
  WriteFileAtomically(path, "old content, longer than the new");
  WriteFileAtomically(path, "new");
  EXPECT_EQ(ReadAll(path), "new");
}

TEST(AtomicFile, FailureNamesThePathAndKeepsWhatWasThere) {
  const std::string dir = testing::TempDir("atomic_fail");
  // A directory cannot be replaced by a file: the rename fails.
  const std::string path = dir + "/taken";
  fs::create_directory(path);
  WriteFileAtomically(path + "/inside.txt", "kept");
  try {
    WriteFileAtomically(path, "x");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'" + path + "'"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ReadAll(path + "/inside.txt"), "kept");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_THROW(WriteFileAtomically(dir + "/no/such/dir/f", "x"),
               std::runtime_error);
}

}  // namespace
}  // namespace mrsim

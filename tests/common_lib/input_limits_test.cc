// The limits every file reader applies before parsing (common/input_limits.h).
#include "common/input_limits.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::string& xml) {
  try {
    CheckXmlLimits(xml, "f.xml");
  } catch (const InputLimitError& e) {
    return e.what();
  }
  return "";
}

TEST(InputLimits, AFileOverTheCapIsRefusedWithoutReadingIt) {
  const std::string dir = testing::TempDir("input_limits_size");
  const std::string path = dir + "/big.xml";
  std::ofstream(path) << "<a/>";
  // Sparse: a 1 GB attribute needs a file beyond the cap, not 1 GB on disk.
  std::filesystem::resize_file(path, kMaxInputFileBytes + 1);
  try {
    ReadFileAtMost(path);
    ADD_FAILURE() << "read it";
  } catch (const InputLimitError& e) {
    EXPECT_EQ(std::string(e.what()),
              path +
                  ": larger than 64 MiB, the most mrsim reads from one "
                  "file");
  }
  std::filesystem::resize_file(path, kMaxInputFileBytes);
  EXPECT_EQ(ReadFileAtMost(path)->size(), kMaxInputFileBytes);
}

TEST(InputLimits, AnEndlessStreamIsRefusedAtTheCap) {
  EXPECT_THROW(ReadFileAtMost("/dev/zero", 1 << 20), InputLimitError);
  EXPECT_FALSE(ReadFileAtMost("/nonexistent/file").has_value());
}

TEST(InputLimits, DeepNestingIsRefusedAtItsLine) {
  std::string xml = "<a>\n";
  for (int i = 0; i < 10000; ++i) xml += "<b>";
  EXPECT_EQ(ErrorOf(xml),
            "f.xml:2: elements nested more than 32 deep, more than any mrsim "
            "file has");
  // Self-closed, closed, commented and quoted tags do not nest.
  std::string flat = "<?xml version=\"1.0\"?><!-- <c><c> --><a x='<b>'>";
  for (int i = 0; i < 100; ++i) flat += "<b/><c></c><![CDATA[<d>]]>";
  EXPECT_EQ(ErrorOf(flat + "</a>"), "");
}

TEST(InputLimits, ALongAttributeIsRefusedAtItsLine) {
  const std::string ok(kMaxXmlAttributeBytes, 'v');
  EXPECT_EQ(ErrorOf("<a\n x=\"" + ok + "\"/>"), "");
  EXPECT_THAT(ErrorOf("<a\n x=\"" + ok + "v\"/>"),
              HasSubstr("f.xml:2: an attribute value longer than 64 KiB"));
}

}  // namespace
}  // namespace mrsim

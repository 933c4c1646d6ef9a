// The gait atlas guard: every line of docs/gait_atlas.csv is measured again
// and must stay within its tolerance (one ctest test per line, so ctest -j
// spreads them), and a deliberate 10 % amplitude change must fail the same
// check.
#include "gait_controller/gait_atlas.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include "bench/gait/task_atlas.h"
#include "gait_controller/atlas_deviation.h"
#include "gait_controller/atlas_table.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

const std::vector<AtlasLine>& Table() {
  static const std::vector<AtlasLine> kTable =
      ReadAtlasTable(std::string(MRSIM_SOURCE_DIR) + "/docs/gait_atlas.csv");
  return kTable;
}

std::vector<std::string> EntryNames() {
  std::vector<std::string> names;
  for (const AtlasEntry& e : AllAtlasEntries()) names.push_back(e.name);
  return names;
}

// "turn-left-0.375" -> "turn_left_0_375": gtest allows only [A-Za-z0-9_].
std::string TestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

class GaitAtlasLine : public ::testing::TestWithParam<std::string> {};

TEST_P(GaitAtlasLine, StaysWithinItsTolerance) {
  const AtlasEntry& entry = FindAtlasEntry(GetParam(), AllAtlasEntries());
  const AtlasLine& line = FindAtlasLine(Table(), entry.name);
  const auto deviations =
      CompareAtlasLine(line, MeasureAtlasValues(entry, line.samples));
  EXPECT_FALSE(AnyBeyond(deviations)) << DescribeAtlasDeviations(deviations);
}

INSTANTIATE_TEST_SUITE_P(Table, GaitAtlasLine,
                         ::testing::ValuesIn(EntryNames()), TestName);

TEST(GaitAtlas, TheTableHasOneLinePerEntryInOrder) {
  std::vector<std::string> in_table;
  for (const AtlasLine& l : Table()) in_table.push_back(l.name);
  EXPECT_EQ(in_table, EntryNames())
      << "regenerate with build/bench/gait/gait_atlas --write "
         "docs/gait_atlas.csv";
}

// The guard works: `forward` with its pitch amplitude 1.1 instead of 1 rad
// is measured exactly as its line is checked, and the check reports it.
TEST(GaitAtlas, ATenPercentAmplitudeChangeFailsTheCheck) {
  const AtlasEntry& entry = FindAtlasEntry("forward");
  const AtlasLine& line = FindAtlasLine(Table(), "forward");
  const auto deviations =
      CompareAtlasLine(line, MeasureAtlasValues(entry, line.samples, 1.1));
  EXPECT_TRUE(AnyBeyond(deviations));
  const std::string message = DescribeAtlasDeviations(deviations);
  EXPECT_THAT(message, HasSubstr("gait atlas line 'forward' moved: speed"));
  EXPECT_THAT(message, HasSubstr("gait_atlas --write docs/gait_atlas.csv"));
}

// Also on a line checked by its mean over five runs: sidewinding, whose
// heading moves by tenths of a degree for a 0.1 % change.
TEST(GaitAtlas, ATenPercentAmplitudeChangeOfAChaoticLineFailsTheCheck) {
  const AtlasEntry& entry = FindAtlasEntry("sidewind");
  const AtlasLine& line = FindAtlasLine(Table(), "sidewind");
  ASSERT_EQ(line.samples, 5);
  const auto deviations =
      CompareAtlasLine(line, MeasureAtlasValues(entry, line.samples, 1.1));
  EXPECT_TRUE(AnyBeyond(deviations));
}

// The other side: the tolerances are not so tight that noise fails them.
// Scaling the amplitudes by 1.0005 gives a chaotic gait a fresh draw of
// its five runs (as another machine's last bits might), and lateral
// undulation, the most chaotic line, must still pass.
TEST(GaitAtlas, AChangeFarBelowAnythingMeantPassesTheCheck) {
  for (const char* name : {"forward", "serpenoid"}) {
    const AtlasEntry& entry = FindAtlasEntry(name);
    const AtlasLine& line = FindAtlasLine(Table(), name);
    const auto deviations =
        CompareAtlasLine(line, MeasureAtlasValues(entry, line.samples, 1.0005));
    EXPECT_FALSE(AnyBeyond(deviations)) << DescribeAtlasDeviations(deviations);
  }
}

}  // namespace
}  // namespace mrsim

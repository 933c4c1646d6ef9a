#include "optimizer/search/genome.h"

#include <gtest/gtest.h>

#include "sim_core/scenario/scenario_schema.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

TEST(OptimizerGenome, ReadsGenesWithLimitsToggleAndStart) {
  const GenomeSpec spec = ReadGenomeString(R"(<genome robot="snake">
  <gene name="A_pitch" lower="0" upper="1.57" start="1"/>
  <gene name="T" lower="1" upper="8" start="4" enabled="false"/>
  <gene name="module_count" lower="6" upper="14" start="11"/>
</genome>)",
                                           "g.xml");
  EXPECT_EQ(spec.robot, "snake");
  ASSERT_EQ(spec.size(), 3);
  EXPECT_EQ(spec.genes[0].upper, 1.57);
  EXPECT_FALSE(spec.genes[1].enabled);
  EXPECT_TRUE(spec.genes[2].integer);
  EXPECT_EQ(spec.StartGenome(), (Genome{1, 4, 11}));
  EXPECT_EQ(ReadGenomeString(WriteGenomeString(spec), "again").genes.size(),
            3u);
  EXPECT_EQ(WriteGenomeString(ReadGenomeString(WriteGenomeString(spec), "x")),
            WriteGenomeString(spec));
}

// The studio starts from the built-in genome, the CLI examples from the
// file: the same genes, limits and starts.
TEST(OptimizerGenome, BuiltInForwardGaitIsTheExampleFile) {
  GenomeSpec file =
      ReadGenomeFile(testing::SourcePath("scenarios/forward_gait.genome.xml"));
  file.robot.clear();  // the file names the example's robot
  EXPECT_EQ(WriteGenomeString(ForwardGaitGenome()), WriteGenomeString(file));
  EXPECT_NO_THROW(ForwardGaitGenome().Validate("built-in"));
}

// Limits no individual could live with are refused at once, naming the
// gene and line, not found out as failures in the middle of the run.
TEST(OptimizerGenome, LimitsTheSimulatorWouldRefuseAreNamed) {
  const auto error = [](const std::string& gene) {
    try {
      ReadGenomeString("<genome>\n" + gene + "\n</genome>", "g.xml");
    } catch (const GenomeError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(
      error(R"(<gene name="joint_kp" lower="-5" upper="1" start="0.5"/>)"),
      "g.xml:2: gene 'joint_kp': lower -5 is outside what joint_kp can "
      "take (>= 0 and <= 1000000000)");
  EXPECT_NE(
      error(R"(<gene name="module_scale" lower="0" upper="2" start="1"/>)")
          .find("lower 0 is outside what module_scale can take (> 0 and "
                "<= 10000)"),
      std::string::npos);
  EXPECT_NE(error(R"(<gene name="T" lower="0" upper="2" start="1"/>)")
                .find("lower 0 is outside what T can take"),
            std::string::npos);
  EXPECT_NE(
      error(R"(<gene name="module_count" lower="0" upper="3" start="2"/>)")
          .find("module_count"),
      std::string::npos);
  // A disabled gene only ever takes its start.
  EXPECT_EQ(
      error(
          R"(<gene name="joint_kp" lower="-5" upper="1" start="0.5" enabled="false"/>)"),
      "accepted");
  // A misspelt attribute is not silently ignored.
  EXPECT_EQ(
      error(R"(<gene name="T" lower="1" upper="2" start="1" enable="false"/>)"),
      "g.xml:2: unknown attribute 'enable' (expected name, lower, upper, "
      "start, enabled, integer)");
}

TEST(OptimizerGenome, BadFileNamesLineAndField) {
  try {
    ReadGenomeString(
        "<genome>\n<gene name=\"T\" lower=\"1\" upper=\"x\" "
        "start=\"2\"/>\n</genome>",
        "bad.xml");
    FAIL();
  } catch (const GenomeError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.xml:2"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("upper"), std::string::npos);
  }
}

TEST(OptimizerGenome, RejectsUnknownNamesAndStartOutsideLimits) {
  EXPECT_THROW(ReadGenomeString("<genome><gene name=\"speed\" lower=\"0\" "
                                "upper=\"1\" start=\"0\"/></genome>",
                                "g.xml"),
               GenomeError);
  EXPECT_THROW(ReadGenomeString("<genome><gene name=\"T\" lower=\"1\" "
                                "upper=\"2\" start=\"3\"/></genome>",
                                "g.xml"),
               GenomeError);
  EXPECT_THROW(ReadGenomeFile("/nonexistent/genome.xml"), GenomeError);
}

TEST(OptimizerGenome, HostileFilesAreRefusedWithTheirLine) {
  const auto error = [](const std::string& xml) {
    try {
      ReadGenomeString(xml, "g.xml");
    } catch (const GenomeError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // A billion modules, or a negative count, is no body to evaluate.
  EXPECT_EQ(error("<genome>\n<gene name=\"module_count\" lower=\"1\" "
                  "upper=\"1e9\" start=\"2\"/>\n</genome>"),
            "g.xml:2: gene 'module_count': upper 1000000000 is outside what "
            "module_count can take (>= 1 and <= 1000; " +
                std::string(kMaxModulesWhy) + ")");
  EXPECT_NE(error("<genome>\n<gene name=\"module_count\" lower=\"-5\" "
                  "upper=\"3\" start=\"2\"/>\n</genome>")
                .find("g.xml:2: gene 'module_count': lower -5"),
            std::string::npos);
  EXPECT_NE(error("<genome>\n<gene name=\"T\" lower=\"NaN\" upper=\"3\" "
                  "start=\"2\"/>\n</genome>")
                .find("g.xml:2: attribute 'lower': expected a number"),
            std::string::npos);
  std::string deep = "<genome>\n";
  for (int i = 0; i < 10000; ++i) deep += "<gene>";
  EXPECT_EQ(error(deep),
            "g.xml:2: elements nested more than 32 deep, more than any mrsim "
            "file has");
}

}  // namespace
}  // namespace mrsim

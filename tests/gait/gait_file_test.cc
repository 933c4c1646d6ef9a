#include "gait_controller/gait_file.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "gait_controller/gait_presets.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

std::string ErrorOf(const std::string& xml) {
  try {
    ReadGaitString(xml, "bad.xml");
  } catch (const GaitFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(GaitFile, EveryPresetRoundTripsExactly) {
  for (const Gait& g : GaitPresets()) {
    const std::string text = WriteGaitString(g);
    const Gait back = ReadGaitString(text, g.name + ".xml");
    EXPECT_EQ(back, g) << text;
    EXPECT_EQ(WriteGaitString(back), text);
  }
}

TEST(GaitFile, OddNumbersAndOverridesRoundTrip) {
  Gait g;
  g.name = "optimised gen 40";
  g.kind = GaitKind::kSidewind;
  g.parameters = GaitParameters::FromVector(
      {0.1 + 0.2, 1.0 / 3.0, -2.718281828459045, 1e-9, 3.3333333333333335,
       -0.123456789012345678, 0.5});
  g.parameters.pitch_yaw_lag = 1.2345678901234567;
  g.parameters.overrides.push_back({3, 0.25, std::nullopt, -0.01});
  g.parameters.overrides.push_back({0, std::nullopt, 7.0, std::nullopt});
  const std::string dir = testing::TempDir("gait_file_odd");
  const std::string path = dir + "/g.xml";
  WriteGaitFile(g, path);
  EXPECT_EQ(ReadGaitFile(path), g);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(GaitFile, BadFilesNameLineAndField) {
  const std::string head = "<?xml version=\"1.0\"?>\n<gait name=\"x\">\n";
  const std::string seven =
      "<A_pitch>1</A_pitch><A_yaw>0</A_yaw><phi_pitch>2.5</phi_pitch>"
      "<phi_yaw>0</phi_yaw><T>4</T><offset_pitch>0</offset_pitch>"
      "<offset_yaw>0</offset_yaw>\n";
  EXPECT_EQ(ErrorOf(head + seven + "</gait>"), "no error");

  std::string e = ErrorOf(head + seven + "<T>fast</T>\n</gait>");
  EXPECT_NE(e.find("bad.xml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("gait/T"), std::string::npos) << e;

  e = ErrorOf(head + "<A_pitch>1</A_pitch>\n<A_yaw>fast</A_yaw></gait>");
  EXPECT_NE(e.find("bad.xml:4: gait/A_yaw: expected a number, got 'fast'"),
            std::string::npos)
      << e;

  e = ErrorOf(head + "<A_pitch>1</A_pitch>\n<A_pitch>2</A_pitch></gait>");
  EXPECT_NE(e.find("bad.xml:4: gait/A_pitch: repeated"), std::string::npos)
      << e;

  e = ErrorOf(head + "<A_pitch>1</A_pitch>\n</gait>");
  EXPECT_NE(e.find("gait/A_yaw: missing"), std::string::npos) << e;

  e = ErrorOf(head + seven + "<amplitude>1</amplitude>\n</gait>");
  EXPECT_NE(e.find("bad.xml:4: gait/amplitude: unknown element"),
            std::string::npos)
      << e;

  e = ErrorOf(head + seven + "<joint amplitude=\"1\"/>\n</gait>");
  EXPECT_NE(e.find("missing attribute index"), std::string::npos) << e;

  e = ErrorOf("<gait name=\"x\" kind=\"hop\">" + seven + "</gait>");
  EXPECT_NE(e.find("gait/@kind"), std::string::npos) << e;

  e = ErrorOf("<gait><A_pitch>1</gait>");
  EXPECT_NE(e.find("malformed XML"), std::string::npos) << e;

  e = ErrorOf("<scenario/>");
  EXPECT_NE(e.find("expected the root element <gait>"), std::string::npos) << e;

  std::string neg = seven;
  neg.replace(neg.find("<T>4</T>"), 8, "<T>-1</T>");
  e = ErrorOf(head + neg + "</gait>");
  EXPECT_NE(e.find("gait parameter T"), std::string::npos) << e;
  // Out of range names the line of the element holding the value.
  std::string lines = seven;
  lines.replace(lines.find("<T>4</T>"), 8, "\n\n<T>0.01</T>\n");
  e = ErrorOf(head + lines + "</gait>");
  EXPECT_NE(e.find("bad.xml:5: gait parameter T:"), std::string::npos) << e;
  e = ErrorOf(head + seven + "\n<joint index=\"1\" amplitude=\"9\"/>\n</gait>");
  EXPECT_NE(e.find("bad.xml:5: gait parameter joint override 0"),
            std::string::npos)
      << e;

  EXPECT_THROW(ReadGaitFile("/nonexistent/gait.xml"), GaitFileError);
}

TEST(GaitFile, WriteToUnwritablePlaceKeepsNothingHalfWritten) {
  Gait g = *FindGaitPreset("forward");
  EXPECT_THROW(WriteGaitFile(g, "/nonexistent-dir/g.xml"), GaitFileError);
}

TEST(GaitFile, ResolvesPresetPathAndSearchPath) {
  EXPECT_EQ(ResolveGait("turn-sharp").name, "turn-sharp");
  const std::string dir = testing::TempDir("gait_file_resolve");
  Gait g = *FindGaitPreset("forward");
  g.name = "best";
  g.parameters.amplitude_pitch = 0.77;
  WriteGaitFile(g, dir + "/best.xml");
  EXPECT_EQ(ResolveGait(dir + "/best.xml"), g);
  setenv("MRSIM_GAIT_PATH", ("/nonexistent:" + dir).c_str(), 1);
  EXPECT_EQ(ResolveGait("best"), g);
  try {
    ResolveGait("moonwalk");
    FAIL() << "no error";
  } catch (const GaitFileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown gait 'moonwalk'"), std::string::npos);
    EXPECT_NE(what.find("sidewind-1"), std::string::npos);
  }
  unsetenv("MRSIM_GAIT_PATH");
}

TEST(GaitFile, HostileFilesAreRefusedWithTheirLine) {
  std::string deep = "<gait name=\"g\">\n";
  for (int i = 0; i < 10000; ++i) deep += "<joint>";
  EXPECT_EQ(ErrorOf(deep),
            "bad.xml:2: elements nested more than 32 deep, more than any "
            "mrsim file has");
  std::string many = "<gait name=\"g\">\n";
  for (int i = 0; i < 1001; ++i) many += "<joint index=\"1\"/>\n";
  EXPECT_EQ(ErrorOf(many + "</gait>"),
            "bad.xml:1002: gait/joint: more than 1000 joint "
            "overrides");
  EXPECT_EQ(ErrorOf("<gait name=\"g\">\n<T>NaN</T></gait>"),
            "bad.xml:2: gait/T: expected a number, got 'NaN'");
  const std::string dir = testing::TempDir("gait_file_hostile");
  const std::string big = dir + "/big.xml";
  std::ofstream(big) << "<gait>";
  fs::resize_file(big, size_t{64} << 20 | 1);
  try {
    ReadGaitFile(big);
    ADD_FAILURE() << "read it";
  } catch (const GaitFileError& e) {
    EXPECT_EQ(std::string(e.what()),
              big + ": larger than 64 MiB, the most mrsim reads from one file");
  }
}

}  // namespace
}  // namespace mrsim

// mrsim-scenario, run as a real program: exit codes, output, and that the
// exported MJCF of every example compiles in MuJoCo.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

struct Result {
  int code = -1;
  std::string output;  // stdout and stderr
};

Result RunTool(const std::vector<std::string>& args, const std::string& dir) {
  std::vector<std::string> argv = {
      BinaryPath("sim_core/scenario_tool/mrsim-scenario")};
  argv.insert(argv.end(), args.begin(), args.end());
  ChildProcess child(argv, dir + "/tool.log");
  Result r;
  r.code = child.Wait(60);
  r.output = child.Output();
  return r;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Example(const std::string& name) {
  return SourcePath("scenarios/" + name);
}

TEST(ScenarioTool, ValidateAcceptsEveryExample) {
  const std::string dir = TempDir("tool_validate");
  for (const char* name : {"snake11.xml", "case_study.xml", "terrain.xml"}) {
    const Result r = RunTool({"validate", Example(name)}, dir);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("ok"));
  }
}

TEST(ScenarioTool, ValidateExitsTwoWithTheErrorOnABadFile) {
  const std::string dir = TempDir("tool_validate_bad");
  std::string xml = ReadText(Example("snake11.xml"));
  xml.replace(xml.find("<Kp>10</Kp>"), 11, "<Kp>fast</Kp>");
  std::ofstream(dir + "/bad.xml") << xml;
  const Result r = RunTool({"validate", dir + "/bad.xml"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.output, HasSubstr(dir + "/bad.xml:"));
  EXPECT_THAT(r.output,
              HasSubstr("Scenario/robot[1]/modules/Module[1]/joint/Kp: "
                        "expected a number, got 'fast'"));
  const Result missing = RunTool({"validate", dir + "/missing.xml"}, dir);
  EXPECT_EQ(missing.code, 2);
  EXPECT_THAT(missing.output, HasSubstr("missing.xml"));
}

TEST(ScenarioTool, BadCommandLineExitsTwo) {
  const std::string dir = TempDir("tool_bad_args");
  EXPECT_EQ(RunTool({}, dir).code, 2);
  const auto unknown = RunTool({"frobnicate"}, dir);
  EXPECT_EQ(unknown.code, 2);
  EXPECT_THAT(unknown.output, HasSubstr("unknown subcommand 'frobnicate'"));
  EXPECT_THAT(unknown.output, Not(HasSubstr("did you mean")));
  EXPECT_THAT(
      RunTool({"valdate", "x.xml"}, dir).output,
      HasSubstr("unknown subcommand 'valdate' (did you mean validate?)"));
  EXPECT_EQ(RunTool({"new", "--pattern", "roll"}, dir).code, 2);
  EXPECT_EQ(RunTool({"new", "--modules", "0"}, dir).code, 2);
  EXPECT_EQ(RunTool({"new", "--sensors", "x,y"}, dir).code, 2);
  EXPECT_EQ(
      RunTool({"convert", Example("snake11.xml"), "-", "--scale", "0"}, dir)
          .code,
      2);
  EXPECT_EQ(RunTool({"--help"}, dir).code, 0);
}

TEST(ScenarioTool, InfoReportsRobotsSensorsMassObjectsAndTerrain) {
  const std::string dir = TempDir("tool_info");
  const Result study = RunTool({"info", Example("case_study.xml")}, dir);
  EXPECT_EQ(study.code, 0) << study.output;
  EXPECT_THAT(study.output,
              HasSubstr("case_study: 5 modules (3 pitch, 2 yaw)"));
  EXPECT_THAT(study.output, HasSubstr("6 sensor modules, 6 force sensors, 1 "
                                      "distance sensor,"));
  EXPECT_THAT(study.output, HasSubstr("mass 0.831 kg"));
  EXPECT_THAT(study.output, HasSubstr("scene objects: 1 (1 Sphere)"));
  EXPECT_THAT(study.output, HasSubstr("terrain: flat ground"));
  const Result terrain = RunTool({"info", Example("terrain.xml")}, dir);
  EXPECT_EQ(terrain.code, 0) << terrain.output;
  EXPECT_THAT(terrain.output, HasSubstr("(64x64 px), 3.2 x 3.2 m, height 0.3"));
  EXPECT_THAT(terrain.output, HasSubstr("3 Box (static)"));
}

TEST(ScenarioTool, ExportedMjcfOfEveryExampleCompiles) {
  const std::string dir = TempDir("tool_export");
  for (const char* name : {"snake11.xml", "case_study.xml", "terrain.xml"}) {
    SCOPED_TRACE(name);
    const std::string out = dir + "/" + name;
    const Result r = RunTool({"export-mjcf", Example(name), "-o", out}, dir);
    ASSERT_EQ(r.code, 0) << r.output;
    char error[1000] = "";
    mjModel* model = mj_loadXML(out.c_str(), nullptr, error, sizeof error);
    ASSERT_NE(model, nullptr) << error;
    EXPECT_GT(model->nbody, 1);
    EXPECT_GT(model->njnt, 0);
    mj_deleteModel(model);
  }
}

TEST(ScenarioTool, NewWritesAChainThatValidates) {
  const std::string dir = TempDir("tool_new");
  const std::string out = dir + "/chain.xml";
  const Result r =
      RunTool({"new", "--modules", "4", "--pattern", "pitch-yaw",
               "--sensors=-1,1", "--force-sensors", "--front-distance-sensor",
               "--name", "worm", "-o", out},
              dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("wrote " + out), std::string::npos) << r.output;
  const Scenario s = ReadScenarioFile(out);
  ASSERT_EQ(s.robots.size(), 1u);
  EXPECT_EQ(s.robots[0].name, "worm");
  EXPECT_EQ(s.robots[0].modules.size(), 4u);
  EXPECT_EQ(s.robots[0].modules[1].axis, Axis::kYaw);
  ASSERT_EQ(s.robots[0].sensor_modules.size(), 2u);
  EXPECT_EQ(s.robots[0].sensor_modules[1].left_mod_nr, 1);
  EXPECT_EQ(s.robots[0].sensor_modules[0].distance_sensors.size(), 1u);
  EXPECT_EQ(RunTool({"validate", out}, dir).code, 0);
}

TEST(ScenarioTool, ConvertTurnsAUnityFileIntoANativeOne) {
  const std::string dir = TempDir("tool_convert");
  const Scenario native = ReadScenarioFile(Example("case_study.xml"));
  // A Unity file in centimetres.
  Scenario centimetres = native;
  ScaleLengths(&centimetres, 100);
  WriteScenarioFile(centimetres, dir + "/unity.xml",
                    FrameConvention::kUnityYUp);
  EXPECT_THAT(ReadText(dir + "/unity.xml"), HasSubstr("frame=\"unity-y-up\""));
  const Result r = RunTool(
      {"convert", dir + "/unity.xml", dir + "/native.xml", "--scale", "0.01"},
      dir);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string text = ReadText(dir + "/native.xml");
  EXPECT_THAT(text, HasSubstr("frame=\"z-up\""));
  const Scenario back = ReadScenarioFile(dir + "/native.xml");
  // Scaling by 100 then 0.01 is not exact in binary; compare positions.
  ASSERT_EQ(back.robots.size(), 1u);
  for (size_t i = 0; i < native.robots[0].modules.size(); ++i) {
    EXPECT_TRUE(back.robots[0].modules[i].position.isApprox(
        native.robots[0].modules[i].position, 1e-12));
    EXPECT_TRUE(back.robots[0].modules[i].frames[0].quat_rotation.isApprox(
        native.robots[0].modules[i].frames[0].quat_rotation, 1e-12));
  }
  EXPECT_TRUE(back.scene_objects[0].position.isApprox(
      native.scene_objects[0].position, 1e-12));
  EXPECT_NEAR(back.settings.gravity.z(), -9.81, 1e-12);
}

TEST(ScenarioTool, FailedConvertLeavesAnExistingOutputUntouched) {
  const std::string dir = TempDir("tool_convert_bad");
  std::ofstream(dir + "/bad.xml") << "<Scenario><robot>";
  std::ofstream(dir + "/out.xml") << "precious";
  const Result r =
      RunTool({"convert", dir + "/bad.xml", dir + "/out.xml"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.output, HasSubstr("malformed XML"));
  EXPECT_EQ(ReadText(dir + "/out.xml"), "precious");
}

// The whole import: a file the original wrote converts, validates, exports
// to MJCF that MuJoCo compiles, and runs in the simulator process.
TEST(ScenarioTool, OriginalFileConvertsValidatesExportsAndRuns) {
  const std::string dir = TempDir("tool_original");
  const std::string native = dir + "/native.xml";
  Result r = RunTool({"convert", "--from", "unity-y-up",
                      Example("mrsim_original.xml"), native, "--scale", "0.01"},
                     dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(ReadText(native), HasSubstr("frame=\"z-up\""));
  r = RunTool({"validate", native}, dir);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("ok (1 robot, 2 scene objects)"));
  r = RunTool({"export-mjcf", native, "-o", dir + "/native.mjcf.xml"}, dir);
  ASSERT_EQ(r.code, 0) << r.output;
  char error[1000] = {0};
  MjModelPtr model(mj_loadXML((dir + "/native.mjcf.xml").c_str(), nullptr,
                              error, sizeof(error)));
  EXPECT_TRUE(model) << error;
  ChildProcess sim(
      {BinaryPath("sim_core/sim_process/mrsim-sim"), native, "--lcm-url",
       TestLcmUrl(7921), "--clock", "fast", "--duration", "1"},
      dir + "/sim.log");
  EXPECT_EQ(sim.Wait(120), 0) << sim.Output();
  EXPECT_THAT(sim.Output(), HasSubstr("stopped (duration reached)"));
  // Without --from the file is taken as Z-up; a file that says its frame
  // cannot be read as another.
  r = RunTool({"convert", "--from", "unity-y-up", native, dir + "/again.xml"},
              dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.output, HasSubstr("Scenario/@frame: the file says"));
}

TEST(ScenarioTool, ValidateRefusesAStaticFrameOfMassZero) {
  const std::string dir = TempDir("validate_tool_mass");
  ChainOptions options;
  options.name = "r";
  options.modules = 2;
  Scenario s;
  s.robots.push_back(MakeChain(options));
  s.robots[0].modules[0].frames[0].is_static = true;
  s.robots[0].modules[0].frames[0].mass = 0;
  WriteScenarioFile(s, dir + "/static.xml");
  const Result r = RunTool({"validate", dir + "/static.xml"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.output, HasSubstr(dir + "/static.xml:"));
  EXPECT_THAT(r.output,
              HasSubstr("Scenario/robot[1]/modules/Module[1]/frames/Frame[1]/"
                        "mass: expected a positive value, got 0"));
}

TEST(ScenarioTool, ValidateExitsTwoNamingPartsThatOverlapAtTheStart) {
  const std::string dir = TempDir("tool_validate_overlap");
  Scenario s = ReadScenarioFile(Example("case_study.xml"));
  SceneObject crate;
  crate.guid = "crate";
  crate.is_static = true;
  crate.size = Eigen::Vector3d(0.3, 0.3, 0.3);
  crate.position = s.robots[0].modules[2].position;
  s.scene_objects.push_back(crate);
  WriteScenarioFile(s, dir + "/boxed.xml");
  const Result r = RunTool({"validate", dir + "/boxed.xml"}, dir);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: " + dir + "/boxed.xml:"));
  EXPECT_THAT(r.output,
              HasSubstr("module 2 front frame overlaps scene object "));
}

TEST(ScenarioTool, ExportStlWritesThePartsAndTheListIntoTheFolder) {
  const std::string dir = TempDir("tool_export_stl");
  const Result r =
      RunTool({"export-stl", Example("case_study.xml"), dir + "/out"}, dir);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("distinct) in " + dir + "/out"));
  const std::string csv = ReadText(dir + "/out/parts.csv");
  EXPECT_THAT(csv, HasSubstr("part,file,count,"));
  EXPECT_THAT(csv, HasSubstr(".stl,"));
  const Result missing =
      RunTool({"export-stl", dir + "/missing.xml", dir + "/out2"}, dir);
  EXPECT_EQ(missing.code, 2) << missing.output;
}

}  // namespace
}  // namespace mrsim

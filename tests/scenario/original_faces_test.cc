// Files the original MRSim wrote load and their distance sensors look
// where they looked in the original (docs/scenario.md, "Faces of the
// original's sensors").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim_core/scenario/face_geometry.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario_tool/scenario_command.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::SourcePath;
using testing::TempDir;

std::string Replace(std::string text, const std::string& from,
                    const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The bundled original file with its end sensor module's face-4 sensor
// looking along (0, 0, 1), Unity's forward, and the ball four units ahead
// of that face (its centre 5 + 4 + 5 units from the module's centre).
std::string FrontSensorFacingABall(const std::string& dir) {
  std::ifstream in(SourcePath("scenarios/mrsim_original.xml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = Replace(text.str(),
                            "            <ray_Direction>\n"
                            "              <x>1</x>\n"
                            "              <y>0</y>\n"
                            "              <z>0</z>\n",
                            "            <ray_Direction>\n"
                            "              <x>0</x>\n"
                            "              <y>0</y>\n"
                            "              <z>1</z>\n");
  xml = Replace(xml,
                "        <x>60</x>\n"
                "        <y>5</y>\n"
                "        <z>0</z>\n",
                "        <x>15</x>\n"
                "        <y>5.5</y>\n"
                "        <z>14</z>\n");
  const std::string path = dir + "/front_sensor.xml";
  std::ofstream(path) << xml;
  return path;
}

TEST(OriginalFaces, FrontSensorOfAnOriginalFileReadsTheBallAheadOfIt) {
  const std::string dir = TempDir("original_front_sensor");
  const std::string path = FrontSensorFacingABall(dir);
  ASSERT_TRUE(IsOriginalMrsimFile(path));
  const Scenario s = ReadScenarioFile(path, kOriginalMrsimReadOptions);
  const SensorModule& sm = s.robots.at(0).sensor_modules.at(0);
  const DistanceSensor& front = sm.distance_sensors.at(0);
  // Unity's (0, 0, 1) is +y in mrsim's frame: the ray leaves through the
  // face it looks out of, not along mrsim's face 4 (+x).
  EXPECT_TRUE(front.ray_direction.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(SensorFaceNormal(front.sensor_position)
                  .isApprox(front.ray_direction.normalized()));
  // The top sensor already looked out of its face and keeps it.
  EXPECT_EQ(sm.distance_sensors.at(1).sensor_position, 2);

  Physics physics(s);
  const RobotState state = physics.ReadRobotState(0);
  ASSERT_EQ(state.sensor_modules.size(), 1u);
  ASSERT_EQ(state.sensor_modules[0].distances.size(), 2u);
  // Four units of 1 cm.
  EXPECT_NEAR(state.sensor_modules[0].distances[0], 0.04, 1e-6);
}

// The regression as a user met it: `mrsim-scenario convert --from
// unity-y-up --scale 0.01` of that file converts (no "the ray of face 4
// (front) runs into ..."), and the converted file's front sensor reads the
// ball 4 cm ahead.
TEST(OriginalFaces, ConvertFromUnityYUpKeepsTheFrontSensorOnTheBall) {
  const std::string dir = TempDir("original_front_convert");
  const std::string in = FrontSensorFacingABall(dir);
  const std::string out = dir + "/converted.xml";
  std::vector<std::string> args = {"mrsim-scenario", "convert", "--from",
                                   "unity-y-up",     in,        out,
                                   "--scale",        "0.01"};
  CLI::App app;
  ScenarioCommand command;
  AddScenarioFlags(app, command);
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
  std::ostringstream text, info;
  ASSERT_NO_THROW(RunScenarioCommand(command, text, info)) << info.str();

  const Scenario s = ReadScenarioFile(out);  // a native file now
  const SensorModule& sm = s.robots.at(0).sensor_modules.at(0);
  EXPECT_TRUE(SensorFaceNormal(sm.distance_sensors.at(0).sensor_position)
                  .isApprox(sm.distance_sensors.at(0).ray_direction));
  Physics physics(s);
  const RobotState state = physics.ReadRobotState(0);
  ASSERT_EQ(state.sensor_modules.at(0).distances.size(), 2u);
  EXPECT_NEAR(state.sensor_modules[0].distances[0], 0.04, 1e-6);
}

// Files mrsim writes name their frame: their faces are mrsim's and are
// kept even when a ray looks back through its module.
TEST(OriginalFaces, FilesMrsimWroteInUnityFrameKeepTheirFaces) {
  const std::string dir = TempDir("original_faces_kept");
  Scenario s =
      ReadScenarioFile(FrontSensorFacingABall(dir), kOriginalMrsimReadOptions);
  DistanceSensor& top = s.robots[0].sensor_modules[0].distance_sensors[1];
  top.ray_direction = Eigen::Vector3d(1, 0, 0);  // looks along its face
  const std::string unity = WriteScenarioString(s, FrameConvention::kUnityYUp);
  const Scenario back = ReadScenarioString(unity, "u.xml", dir);
  EXPECT_EQ(
      back.robots[0].sensor_modules[0].distance_sensors[1].sensor_position, 2);
}

}  // namespace
}  // namespace mrsim

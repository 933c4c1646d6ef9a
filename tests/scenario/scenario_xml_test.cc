// Scenario files: round trips, the Unity frame, and every validation error
// naming the file, line, element path and what was expected.
#include "sim_core/scenario/scenario_xml.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim_core/mesh/base64.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::SourcePath;
using ::testing::StartsWith;
using testing::TempDir;

const char* const kExamples[] = {"snake11.xml", "case_study.xml",
                                 "terrain.xml"};

// A small valid file using every kind of robot part; tests break one thing.
const char kTemplate[] = R"(<?xml version="1.0" encoding="utf-8"?>
<Scenario xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns:xsd="http://www.w3.org/2001/XMLSchema" frame="z-up">
  <robot>
    <name>r</name>
    <modules xmlns="Assembly">
      <Module>
        <mod_Nr>0</mod_Nr>
        <axis>Pitch</axis>
        <frames>
          <Frame><guid>f0</guid><mass>0.05</mass></Frame>
          <Frame><guid>f1</guid><scale><x>0.05</x><y>0.05</y><z>0.05</z></scale></Frame>
        </frames>
        <joint><guid>j0</guid><leftFrameGuid>f0</leftFrameGuid><rightFrameGuid>f1</rightFrameGuid><type>Hinge</type><lowerRangeLimit>-1</lowerRangeLimit><upperRangeLimit>1</upperRangeLimit><Kp>10</Kp></joint>
      </Module>
    </modules>
    <sensorModules xmlns="Assembly">
      <SensorModule>
        <guid>s0</guid><leftMod_Nr>0</leftMod_Nr><rightMod_Nr>-1</rightMod_Nr>
        <forceSensor><guid>fs0</guid><sensorPosition>0</sensorPosition></forceSensor>
        <forceSensorLock><guid>fl0</guid><leftFrameGuid>s0</leftFrameGuid><rightFrameGuid>fs0</rightFrameGuid><type>Lock</type></forceSensorLock>
        <distanceSensors>
          <DistanceSensor><guid>d0</guid><sensorPosition>4</sensorPosition></DistanceSensor>
        </distanceSensors>
        <distanceSensorLocks><Joint><guid>dl0</guid><leftFrameGuid>s0</leftFrameGuid><rightFrameGuid>d0</rightFrameGuid><type>Lock</type></Joint></distanceSensorLocks>
        <size><x>0.05</x><y>0.05</y><z>0.05</z></size>
      </SensorModule>
    </sensorModules>
    <locks xmlns="Assembly">
      <Joint><guid>l0</guid><leftFrameGuid>f1</leftFrameGuid><rightFrameGuid>s0</rightFrameGuid><type>Lock</type></Joint>
    </locks>
  </robot>
  <scene><guid>scene</guid><position><x>0</x><y>0</y><z>-0.1</z></position></scene>
  <sceneObjects xmlns="Assembly">
    <SceneObject><guid>ball</guid><shape>Sphere</shape><mass>0.2</mass></SceneObject>
  </sceneObjects>
</Scenario>
)";

const char kModulePath[] = "Scenario/robot[1]/modules/Module[1]";
const char kSensorPath[] = "Scenario/robot[1]/sensorModules/SensorModule[1]";

// Replaces the first occurrence of `from` (which must exist).
std::string Replace(std::string text, const std::string& from,
                    const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the template";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// 1-based line of the first occurrence of `needle`, as "t.xml:<line>:".
std::string At(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "no '" << needle << "'";
  const auto line = std::count(text.begin(), text.begin() + at, '\n') + 1;
  return "t.xml:" + std::to_string(line) + ": ";
}

// The ScenarioError message for `xml` (fails the test when it loads).
std::string ErrorOf(const std::string& xml, const std::string& base_dir = ".") {
  try {
    ReadScenarioString(xml, "t.xml", base_dir);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the file loaded but should not have";
  return "";
}

// A double with all the digits it needs to read back exactly.
std::string Num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ScenarioXml, TemplateLoads) {
  const Scenario s = ReadScenarioString(kTemplate, "t.xml", ".");
  ASSERT_EQ(s.robots.size(), 1u);
  EXPECT_EQ(s.robots[0].name, "r");
  ASSERT_TRUE(s.robots[0].sensor_modules[0].force_sensor.has_value());
  EXPECT_EQ(s.robots[0].sensor_modules[0].distance_sensors.size(), 1u);
  // Omitted optional fields take their defaults.
  EXPECT_EQ(s.robots[0].modules[0].joint.max_vel, Joint().max_vel);
  EXPECT_EQ(s.robots[0].modules[0].frames[1].mass, Frame().mass);
  EXPECT_EQ(s.scene_objects[0].shape, PrimitiveShape::kSphere);
}

TEST(ScenarioXml, RoundTripOfEveryExampleGivesEqualObjectsAndBytes) {
  for (const char* name : kExamples) {
    SCOPED_TRACE(name);
    const std::string path = SourcePath(std::string("scenarios/") + name);
    const Scenario first = ReadScenarioFile(path);
    const std::string written = WriteScenarioString(first);
    const Scenario second =
        ReadScenarioString(written, path, SourcePath("scenarios"));
    EXPECT_TRUE(first == second);
    EXPECT_EQ(WriteScenarioString(second), written);
    EXPECT_EQ(WriteScenarioString(first), written);
    // The committed files are in canonical form.
    EXPECT_EQ(ReadText(path), written);
  }
}

// Every field set to something other than its default, including doubles
// that need all 17 digits.
Scenario EveryFieldScenario(const std::string& mesh) {
  ChainOptions options;
  options.name = "alpha";
  options.modules = 3;
  options.pattern = ChainPattern::kPitchYaw;
  options.sensor_after = {-1, 1, 2};
  options.force_sensors = true;
  options.front_distance_sensor = true;
  options.module_mass = 0.1 + 0.2;
  Scenario s;
  s.robots.push_back(MakeChain(options));
  Robot& r = s.robots[0];
  r.modules[1].frames[0].shape = mesh;
  r.modules[1].frames[0].rotation = Eigen::Vector3d(10, -20.5, 1.0 / 3);
  r.modules[1].frames[0].quat_rotation = Eigen::Quaterniond(
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  r.modules[2].frames[1].is_static = true;
  r.modules[2].frames[1].material_name = "rubber & <steel>";
  r.modules[0].joint.kp = 12.345678901234567;
  r.modules[0].joint.max_vel = 1e-7;
  r.modules[0].joint.velocity_gain = 7.5;
  r.modules[1].joint.max_torque = 0.35;
  r.locks[0].break_force = 12.5;
  SensorModule& sm = r.sensor_modules[0];
  sm.force_sensor->force_value = 3.25;
  sm.force_sensor->rotation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
  sm.distance_sensors[0].ray_resolution = 0.05;
  sm.distance_sensors[0].max_ray_distance = 1.75;
  sm.distance_sensors[0].rotation = Eigen::Vector3d(1, 2, 3);
  sm.quat_rotation = Eigen::Quaterniond(0, 1, 0, 0);
  sm.rotation = Eigen::Vector3d(180, 0, 0);
  Robot second = MakeChain([] {
    ChainOptions o;
    o.name = "beta";
    o.modules = 1;
    o.origin = Eigen::Vector3d(0, 1, 0.5);
    return o;
  }());
  s.robots.push_back(second);
  s.scene.guid = "ground";
  s.scene.position = Eigen::Vector3d(-1, -2, -0.125);
  s.scene.material_name = "dirt";
  s.scene.height = 0.3;
  s.scene.meters_per_pixel = 0.02;
  s.scene.height_image = "terrain.png";
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.1, 0.1, 0.1);
  ball.position = Eigen::Vector3d(0.6, 0, 0.05);
  ball.rotation = Eigen::Vector3d(0, 45, 0);
  ball.quat_rotation =
      Eigen::Quaterniond(0.9238795325112867, 0, 0.3826834323650898, 0);
  ball.material_name = "plastic";
  ball.mass = 0.25;
  SceneObject ramp;
  ramp.guid = "ramp";
  ramp.shape = PrimitiveShape::kCapsule;
  ramp.is_static = true;
  ramp.mass = 0;
  // A fixed camera on the static ramp (every field off its default), and
  // one on the moving ball.
  Camera cctv;
  cctv.guid = "cctv";
  cctv.sensor_position = 1;
  cctv.fovy = 42.5;
  cctv.width = 320;
  cctv.height = 200;
  cctv.rate = 12.5;
  cctv.near_clip = 0.05;
  cctv.far_clip = 25;
  cctv.tilt = 30;
  cctv.noise = 2.5;
  cctv.seed = 11;
  ramp.cameras = {cctv};
  ball.cameras.emplace_back().sensor_position = 2;
  SceneObject can;
  can.guid = "can";
  can.shape = PrimitiveShape::kCylinder;
  s.scene_objects = {ball, ramp, can};
  s.contact_frictions.push_back({"plastic", "dirt", 0.25, 0.8, 3e9});
  s.contact_frictions.push_back({"plastic", "plastic", 0, 0.4, 1e6});
  FluidRegion water;
  water.guid = "pond";
  water.position = Eigen::Vector3d(2, 0, -0.5);
  water.size = Eigen::Vector3d(1, 1, 1);
  water.velocity = Eigen::Vector3d(0.1, 0, 0);
  FluidRegion air;
  air.kind = FluidKind::kAir;
  air.density = 1.2;
  air.viscosity = 1.8e-5;
  air.velocity = Eigen::Vector3d(0, -3, 0);
  s.fluid_regions = {water, air};
  s.settings.timestep = 0.001;
  s.settings.gravity = Eigen::Vector3d(0, 0, -1.62);
  Frame loose;
  loose.guid = "loose_frame";
  loose.position = Eigen::Vector3d(3, 3, 0.1);
  s.loose_frames.push_back(loose);
  loose.guid = "loose_door";
  loose.position = Eigen::Vector3d(3, 3.05, 0.1);
  s.loose_frames.push_back(loose);
  SensorModule loose_sensor;
  loose_sensor.guid = "loose_sensor";
  loose_sensor.cameras.emplace_back().tilt = -15;
  s.loose_sensor_modules.push_back(loose_sensor);
  Joint hinge;
  hinge.guid = "loose_hinge";
  hinge.left_frame_guid = "loose_frame";
  hinge.right_frame_guid = "loose_door";
  hinge.lower_range_limit = -0.25;
  hinge.upper_range_limit = 0.5;
  hinge.servo = true;
  hinge.kp = 4.5;
  hinge.max_torque = 0.75;
  s.loose_joints.push_back(hinge);
  return s;
}

std::string WriteMesh(const std::string& dir) {
  // A closed tetrahedron: MuJoCo refuses a mesh without volume.
  std::ofstream(dir + "/part.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                      "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  return "part.obj";
}

TEST(ScenarioXml, RoundTripKeepsEveryField) {
  const std::string dir = TempDir("scenario_every_field");
  std::ifstream png(SourcePath("scenarios/terrain.png"), std::ios::binary);
  std::ofstream(dir + "/terrain.png", std::ios::binary) << png.rdbuf();
  const Scenario s = EveryFieldScenario(WriteMesh(dir));
  const std::string path = dir + "/every.xml";
  WriteScenarioFile(s, path);
  const Scenario back = ReadScenarioFile(path);
  EXPECT_TRUE(back == s);
  EXPECT_EQ(back.base_dir, dir);
  EXPECT_EQ(WriteScenarioString(back), ReadText(path));
  // Equality really looks at fields: change one and it differs.
  Scenario changed = back;
  changed.robots[0].sensor_modules[0].distance_sensors[0].ray_resolution = 8;
  EXPECT_TRUE(changed != s);
  changed = back;
  changed.robots[0].locks[0].break_force = 0;
  EXPECT_TRUE(changed != s);
  changed = back;
  changed.robots[0].modules[1].frames[0].quat_rotation.coeffs()[3] += 1e-16;
  EXPECT_TRUE(changed != s);
  // A scene object's and a loose sensor module's cameras are kept too.
  ASSERT_EQ(back.scene_objects[1].cameras.size(), 1u);
  EXPECT_EQ(back.scene_objects[1].cameras[0].far_clip, 25);
  changed = back;
  changed.scene_objects[1].cameras[0].seed = 12;
  EXPECT_TRUE(changed != s);
  changed = back;
  changed.loose_sensor_modules[0].cameras[0].tilt = 0;
  EXPECT_TRUE(changed != s);
  // A loose hinge's servo and its gains.
  EXPECT_TRUE(back.loose_joints[0].servo);
  EXPECT_EQ(back.loose_joints[0].kp, 4.5);
  changed = back;
  changed.loose_joints[0].servo = false;
  EXPECT_TRUE(changed != s);
}

TEST(ScenarioXml, WritingTwiceGivesIdenticalBytes) {
  const std::string dir = TempDir("scenario_write_twice");
  const Scenario s = EveryFieldScenario(WriteMesh(dir));
  EXPECT_EQ(WriteScenarioString(s), WriteScenarioString(s));
  EXPECT_EQ(WriteScenarioString(s, FrameConvention::kUnityYUp),
            WriteScenarioString(s, FrameConvention::kUnityYUp));
}

TEST(ScenarioXml, ReadsXmlSerializerNamespacesPrefixesAndNil) {
  std::string xml =
      Replace(kTemplate, "<scene>", "<q:scene xmlns:q=\"urn:x\">");
  xml = Replace(xml, "</scene>", "</q:scene>");
  xml = Replace(xml, "<forceSensor>",
                "<forceSensor xsi:nil=\"true\" /><forceSensor>");
  const Scenario s = ReadScenarioString(xml, "t.xml", ".");
  EXPECT_EQ(s.scene.guid, "scene");
  EXPECT_TRUE(s.robots[0].sensor_modules[0].force_sensor.has_value());
}

TEST(ScenarioXml, UnnamedRobotsAreNamedByIndex) {
  const std::string second =
      "<robot><modules><Module><mod_Nr>0</mod_Nr><axis>Yaw</axis><frames>"
      "<Frame><guid>g0</guid></Frame><Frame><guid>g1</guid></Frame>"
      "</frames><joint><guid>gj</guid><leftFrameGuid>g0</leftFrameGuid>"
      "<rightFrameGuid>g1</rightFrameGuid><type>Hinge</type></joint>"
      "</Module></modules></robot>\n  <scene>";
  std::string xml = Replace(kTemplate, "<name>r</name>", "");
  xml = Replace(xml, "<scene>", second);
  const Scenario s = ReadScenarioString(xml, "t.xml", ".");
  ASSERT_EQ(s.robots.size(), 2u);
  EXPECT_EQ(s.robots[0].name, "robot0");
  EXPECT_EQ(s.robots[1].name, "robot1");
  EXPECT_EQ(s.robots[1].modules[0].axis, Axis::kYaw);
}

TEST(ScenarioXml, DuplicateRobotNamesAreRejected) {
  const std::string second =
      "<robot>\n<name>r</name><modules><Module><mod_Nr>0</mod_Nr><axis>Yaw"
      "</axis><frames><Frame><guid>g0</guid></Frame><Frame><guid>g1</guid>"
      "</Frame></frames><joint><guid>gj</guid><leftFrameGuid>g0"
      "</leftFrameGuid><rightFrameGuid>g1</rightFrameGuid><type>Hinge</type>"
      "</joint></Module></modules></robot>\n  <scene>";
  const std::string xml = Replace(kTemplate, "<scene>", second);
  const std::string line = At(xml, "<name>r</name><modules>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(line + "Scenario/robot[2]/name: duplicate robot "
                                "name 'r'"));
}

TEST(ScenarioXml, MalformedXmlNamesTheLine) {
  const std::string xml = Replace(kTemplate, "</joint>", "</jont>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "</jont>") + "Scenario: "
                                                            "malformed XML"));
  // In words, not tinyxml2's error enum.
  EXPECT_THAT(ErrorOf(xml), HasSubstr("closed by another name"));
  EXPECT_THAT(ErrorOf("<Scenario><robot>"), HasSubstr("malformed XML"));
}

TEST(ScenarioXml, WrongRootOrFrameAttributeIsRejected) {
  EXPECT_THAT(ErrorOf("<?xml version=\"1.0\"?>\n<Scene />"),
              StartsWith("t.xml:2: Scene: expected the root element "
                         "<Scenario>"));
  const std::string xml =
      Replace(kTemplate, "frame=\"z-up\"", "frame=\"y-up\"");
  EXPECT_THAT(ErrorOf(xml), StartsWith("t.xml:2: Scenario/@frame: expected "
                                       "frame=\"z-up\" or "
                                       "frame=\"unity-y-up\""));
}

TEST(ScenarioXml, MistypedNumberNamesTheField) {
  const std::string xml = Replace(kTemplate, "<Kp>10</Kp>", "<Kp>fast</Kp>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<Kp>fast") + kModulePath +
                         "/joint/Kp: expected a number, got 'fast'"));
}

TEST(ScenarioXml, MistypedIntegerBoolAndEnumNameTheField) {
  std::string xml =
      Replace(kTemplate, "<mod_Nr>0</mod_Nr>", "<mod_Nr>0.5</mod_Nr>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<mod_Nr>") + kModulePath +
                                       "/mod_Nr: expected an integer, got "
                                       "'0.5'"));
  xml = Replace(kTemplate, "<mass>0.2</mass>",
                "<mass>0.2</mass><isStatic>yes</isStatic>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<isStatic>") +
                         "Scenario/sceneObjects/SceneObject[1]/isStatic: "
                         "expected true or false, got 'yes'"));
  xml = Replace(kTemplate, "<axis>Pitch</axis>", "<axis>Roll</axis>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<axis>") + kModulePath +
                                       "/axis: expected Pitch or Yaw, got "
                                       "'Roll'"));
}

TEST(ScenarioXml, UnknownElementIsRejected) {
  const std::string xml = Replace(kTemplate, "<Kp>10</Kp>", "<KP>10</KP>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<KP>") + kModulePath +
                                       "/joint/KP: unknown element"));
}

TEST(ScenarioXml, ModuleWithoutFramesIsRejected) {
  std::string xml = kTemplate;
  const size_t from = xml.find("        <frames>");
  const size_t to = xml.find("</frames>\n") + std::string("</frames>\n").size();
  xml.erase(from, to - from);
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<Module>") + kModulePath +
                                       "/frames: missing; expected an "
                                       "element <frames>"));
}

TEST(ScenarioXml, ModuleWithOneFrameIsRejected) {
  const std::string xml = Replace(
      kTemplate,
      "          <Frame><guid>f1</guid><scale><x>0.05</x><y>0.05</y><z>0.05"
      "</z></scale></Frame>\n",
      "");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<frames>") + kModulePath +
                                       "/frames: expected 2 <Frame> "
                                       "elements, got 1"));
}

TEST(ScenarioXml, MissingRequiredFieldIsNamed) {
  const std::string xml = Replace(kTemplate, "<type>Hinge</type>", "");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<joint>") + kModulePath +
                                       "/joint/type: missing"));
}

TEST(ScenarioXml, JointNamingAMissingFrameIsRejected) {
  const std::string xml =
      Replace(kTemplate, "<rightFrameGuid>f1</rightFrameGuid><type>Hinge",
              "<rightFrameGuid>nope</rightFrameGuid><type>Hinge");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<joint>") + kModulePath +
                         "/joint/rightFrameGuid: no frame or sensor module "
                         "with guid 'nope' in robot 'r'"));
}

TEST(ScenarioXml, LockNamingAMissingPartIsRejected) {
  const std::string xml =
      Replace(kTemplate, "<rightFrameGuid>s0</rightFrameGuid><type>Lock",
              "<rightFrameGuid>s9</rightFrameGuid><type>Lock");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<guid>l0") +
                                       "Scenario/robot[1]/locks/Joint[1]/"
                                       "rightFrameGuid: no frame"));
}

TEST(ScenarioXml, DuplicateGuidIsRejected) {
  const std::string xml =
      Replace(kTemplate, "<Frame><guid>f1</guid>", "<Frame><guid>f0</guid>");
  const std::string first = At(kTemplate, "<guid>f0</guid>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<guid>f0</guid><scale>") + kModulePath +
                         "/frames/Frame[2]/guid: duplicate guid 'f0' (first "
                         "used at line " +
                         first.substr(6, first.size() - 8)));
  // Across kinds of part too: a scene object reusing a sensor module's.
  const std::string xml2 =
      Replace(kTemplate, "<guid>ball</guid>", "<guid>s0</guid>");
  EXPECT_THAT(ErrorOf(xml2), HasSubstr("Scenario/sceneObjects/SceneObject[1]/"
                                       "guid: duplicate guid 's0'"));
}

TEST(ScenarioXml, ForceSensorPositionOutOfRangeIsRejected) {
  const std::string xml =
      Replace(kTemplate, "<sensorPosition>0</sensorPosition>",
              "<sensorPosition>4</sensorPosition>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<forceSensor>") + kSensorPath +
                                       "/forceSensor/sensorPosition: "
                                       "expected 0..3"));
}

TEST(ScenarioXml, DistanceSensorPositionOutOfRangeIsRejected) {
  for (const char* bad : {"6", "-1"}) {
    const std::string xml =
        Replace(kTemplate, "<sensorPosition>4</sensorPosition>",
                std::string("<sensorPosition>") + bad + "</sensorPosition>");
    EXPECT_THAT(ErrorOf(xml),
                StartsWith(At(xml, "<DistanceSensor>") + kSensorPath +
                           "/distanceSensors/DistanceSensor[1]/"
                           "sensorPosition: expected 0..5"));
  }
}

TEST(ScenarioXml, SecondForceSensorIsRejected) {
  const std::string xml =
      Replace(kTemplate, "        <forceSensorLock>",
              "        <forceSensor><guid>fs1</guid></forceSensor>\n"
              "        <forceSensorLock>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<guid>fs1") + kSensorPath +
                                       "/forceSensor: given twice (first at "
                                       "line"));
}

TEST(ScenarioXml, SeventhDistanceSensorIsRejected) {
  std::string more;
  for (int i = 1; i <= 6; ++i) {
    more += "          <DistanceSensor><guid>d" + std::to_string(i) +
            "</guid></DistanceSensor>\n";
  }
  const std::string xml = Replace(kTemplate, "        </distanceSensors>",
                                  more + "        </distanceSensors>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<guid>d6<") + kSensorPath +
                         "/distanceSensors/DistanceSensor[7]: more than 6 "
                         "<DistanceSensor> in <distanceSensors>"));
  // Six are fine.
  const std::string six = Replace(
      xml, "          <DistanceSensor><guid>d6</guid></DistanceSensor>\n", "");
  EXPECT_NO_THROW(ReadScenarioString(six, "t.xml", "."));
}

TEST(ScenarioXml, NonPositiveMassIsRejected) {
  std::string xml = Replace(kTemplate, "<mass>0.05</mass>", "<mass>0</mass>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<mass>0</mass>") + kModulePath +
                         "/frames/Frame[1]/mass: expected a positive value, "
                         "got 0"));
  xml = Replace(kTemplate, "<mass>0.2</mass>", "<mass>-1</mass>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<mass>-1") +
                         "Scenario/sceneObjects/SceneObject[1]/mass: "
                         "expected a value >= 0, got -1"));
  // Only a static object may weigh nothing.
  xml = Replace(kTemplate, "<mass>0.2</mass>", "<mass>0</mass>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<mass>0</mass>") +
                                       "Scenario/sceneObjects/SceneObject[1]/"
                                       "mass: expected a positive value, got "
                                       "0 (only a static object"));
  xml =
      Replace(xml, "<mass>0</mass>", "<mass>0</mass><isStatic>true</isStatic>");
  EXPECT_NO_THROW(ReadScenarioString(xml, "t.xml", "."));
  // A static frame still needs a mass: the simulator gives it a body.
  xml = Replace(kTemplate, "<Frame><guid>f0</guid><mass>0.05</mass>",
                "<Frame><guid>f0</guid><mass>0</mass><isStatic>true"
                "</isStatic>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<mass>0</mass>") + kModulePath +
                         "/frames/Frame[1]/mass: expected a positive value, "
                         "got 0"));
}

TEST(ScenarioXml, NonPositiveSizeIsRejected) {
  std::string xml =
      Replace(kTemplate, "<z>0.05</z></scale>", "<z>-0.05</z></scale>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<z>-0.05") + kModulePath +
                                       "/frames/Frame[2]/scale: expected "
                                       "positive x, y, z"));
  xml = Replace(kTemplate, "<size><x>0.05</x>", "<size><x>0</x>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<size><x>0<") + kSensorPath +
                                       "/size: expected positive x, y, z"));
}

TEST(ScenarioXml, LowerLimitAboveUpperIsRejected) {
  const std::string xml =
      Replace(kTemplate, "<lowerRangeLimit>-1</lowerRangeLimit>",
              "<lowerRangeLimit>2</lowerRangeLimit>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<joint>") + kModulePath +
                         "/joint/lowerRangeLimit: lower limit 2 is above the "
                         "upper limit 1"));
}

TEST(ScenarioXml, SensorModuleNamingAMissingModuleIsRejected) {
  const std::string xml = Replace(kTemplate, "<leftMod_Nr>0</leftMod_Nr>",
                                  "<leftMod_Nr>5</leftMod_Nr>");
  EXPECT_THAT(ErrorOf(xml), StartsWith(At(xml, "<leftMod_Nr>") + kSensorPath +
                                       "/leftMod_Nr: no module with mod_Nr 5 "
                                       "in robot 'r'"));
}

TEST(ScenarioXml, PartNotJoinedToTheRobotIsRejected) {
  std::string xml = kTemplate;
  const std::string lock = "      <Joint><guid>l0</guid>";
  const size_t from = xml.find(lock);
  xml.erase(from, xml.find("</Joint>\n", from) + 9 - from);
  // Without any lock a sensor module is locked to its neighbour modules...
  EXPECT_NO_THROW(ReadScenarioString(xml, "t.xml", "."));
  // ...but with none it floats (its sensors with it).
  xml =
      Replace(xml, "<leftMod_Nr>0</leftMod_Nr>", "<leftMod_Nr>-1</leftMod_Nr>");
  EXPECT_THAT(ErrorOf(xml),
              StartsWith(At(xml, "<guid>s0") + kSensorPath +
                         "/guid: part 's0' is not joined to the rest of robot "
                         "'r'"));
}

// Parts without a robot: a loose frame hinged to a static one.
const char kLoose[] = R"(<?xml version="1.0" encoding="utf-8"?>
<Scenario>
  <sceneObjects><SceneObject><guid>ball</guid><shape>Sphere</shape></SceneObject></sceneObjects>
  <frames><Frame><guid>post</guid><isStatic>true</isStatic></Frame><Frame><guid>door</guid></Frame></frames>
  <sensorModules><SensorModule><guid>eye</guid></SensorModule></sensorModules>
  <joints><Joint><guid>hinge</guid><leftFrameGuid>post</leftFrameGuid><rightFrameGuid>door</rightFrameGuid><type>Hinge</type></Joint></joints>
</Scenario>
)";

TEST(ScenarioXml, LoosePartsLoadWithoutARobot) {
  const Scenario s = ReadScenarioString(kLoose, "t.xml", ".");
  EXPECT_TRUE(s.robots.empty());
  ASSERT_EQ(s.loose_frames.size(), 2u);
  ASSERT_EQ(s.loose_sensor_modules.size(), 1u);
  ASSERT_EQ(s.loose_joints.size(), 1u);
  EXPECT_EQ(s.loose_joints[0].left_frame_guid, "post");
  const std::string written = WriteScenarioString(s);
  EXPECT_TRUE(ReadScenarioString(written, "t.xml", ".") == s);
  const std::string bad =
      Replace(kLoose, "<rightFrameGuid>door", "<rightFrameGuid>window");
  EXPECT_THAT(ErrorOf(bad),
              StartsWith(At(bad, "<joints>") +
                         "Scenario/joints/Joint[1]/rightFrameGuid: no frame "
                         "or sensor module with guid 'window' among the loose "
                         "parts"));
  // The simulator cannot hinge a loose part to a scene object.
  const std::string object =
      Replace(kLoose, "<rightFrameGuid>door", "<rightFrameGuid>ball");
  EXPECT_THAT(ErrorOf(object),
              StartsWith(At(object, "<joints>") +
                         "Scenario/joints/Joint[1]/rightFrameGuid: no frame "
                         "or sensor module with guid 'ball' among the loose "
                         "parts (it is not a part this joint can join"));
}

// A loose hinge's <servo> is written only when on, so files without one
// are written as before and mean what they meant: a passive hinge.
TEST(ScenarioXml, ALooseHingeServoIsWrittenOnlyWhenOn) {
  Scenario s = ReadScenarioString(kLoose, "t.xml", ".");
  ASSERT_EQ(s.loose_joints.size(), 1u);
  EXPECT_FALSE(s.loose_joints[0].servo);
  EXPECT_THAT(WriteScenarioString(s), Not(HasSubstr("<servo>")));
  s.loose_joints[0].servo = true;
  const std::string on = WriteScenarioString(s);
  EXPECT_THAT(on, HasSubstr("<servo>true</servo>"));
  EXPECT_TRUE(ReadScenarioString(on, "t.xml", ".") == s);
  // Not a bool: named with its line.
  const std::string bad = Replace(on, "<servo>true", "<servo>yes");
  EXPECT_THAT(ErrorOf(bad), HasSubstr("Scenario/joints/Joint[1]/servo: "));
}

TEST(ScenarioXml, UnreadableImageIsRejected) {
  const std::string dir = TempDir("scenario_bad_image");
  std::ofstream(dir + "/noise.png") << "this is not a png";
  const std::string kScene =
      "<scene><guid>scene</guid><position><x>0</x><y>0</y><z>-0.1</z></"
      "position></scene>";
  for (const char* image : {"missing.png", "noise.png", "base64:AAAA"}) {
    SCOPED_TRACE(image);
    const std::string xml =
        Replace(kTemplate, kScene,
                std::string("<scene><guid>scene</guid><position><x>0</x><y>0</"
                            "y><z>-0.1</z></position><height_Image>") +
                    image + "</height_Image></scene>");
    EXPECT_THAT(ErrorOf(xml, dir),
                StartsWith(At(xml, "<height_Image>") +
                           "Scenario/scene/height_Image: cannot read the "
                           "height image"));
  }
}

TEST(ScenarioXml, EmbeddedBase64ImageLoadsAndRoundTrips) {
  std::ifstream png(SourcePath("scenarios/terrain.png"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(png)),
                          std::istreambuf_iterator<char>());
  const std::string encoded =
      Base64Encode(std::vector<unsigned char>(bytes.begin(), bytes.end()));
  const std::string xml =
      Replace(kTemplate,
              "<scene><guid>scene</guid><position><x>0</x><y>0</y><z>-0.1</z></"
              "position></scene>",
              "<scene><guid>scene</guid><position><x>0</x><y>0</y><z>-0.1</z></"
              "position><height_Image>base64:" +
                  encoded + "</height_Image><height>0.2</height></scene>");
  const Scenario s = ReadScenarioString(xml, "t.xml", "/nonexistent");
  EXPECT_EQ(s.scene.height_image, "base64:" + encoded);
  const std::string written = WriteScenarioString(s);
  EXPECT_TRUE(ReadScenarioString(written, "t.xml", "/nonexistent") == s);
}

TEST(ScenarioXml, UnreadableMeshIsRejected) {
  const std::string dir = TempDir("scenario_bad_mesh");
  std::ofstream(dir + "/junk.stl") << "not a mesh at all";
  std::ofstream(dir + "/ascii.stl")
      << "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
         "   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid\n";
  std::ofstream(dir + "/empty.obj") << "# nothing\n";
  std::ofstream(dir + "/model.dae") << "<COLLADA/>";
  // v and f lines, but a face index of 0 (OBJ counts from 1): only MuJoCo's
  // own reader finds it, and the validator asks it.
  std::ofstream(dir + "/zero_index.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                            "v 0 0 1\nf 0 1 2\n";
  WriteMesh(dir);
  const std::pair<const char*, const char*> cases[] = {
      {"missing.obj", "cannot read mesh file"},
      {"zero_index.obj", "zero_index.obj': MuJoCo cannot read it: "},
      {"junk.stl", "is not a valid binary STL"},
      {"ascii.stl", "is an ASCII STL: MuJoCo reads binary STL only"},
      {"empty.obj", "is not a valid OBJ"},
      {"model.dae", "expected Box or a mesh file ending in .obj or .stl"}};
  for (const auto& [mesh, what] : cases) {
    SCOPED_TRACE(mesh);
    const std::string xml = Replace(
        kTemplate, "<Frame><guid>f0</guid>",
        std::string("<Frame><guid>f0</guid><shape>") + mesh + "</shape>");
    EXPECT_THAT(ErrorOf(xml, dir), StartsWith(At(xml, "<shape>") + kModulePath +
                                              "/frames/Frame[1]/shape: "));
    EXPECT_THAT(ErrorOf(xml, dir), HasSubstr(what));
  }
  const std::string good = Replace(kTemplate, "<Frame><guid>f0</guid>",
                                   "<Frame><guid>f0</guid><shape>part.obj"
                                   "</shape>");
  EXPECT_NO_THROW(ReadScenarioString(good, "t.xml", dir));
}

// An embedded mesh is checked as a file is: a design that validates
// compiles (found by the scenario_xml fuzz target).
TEST(ScenarioXml, BrokenEmbeddedMeshIsRejectedAtItsFrame) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 0 1 2\n";
  const std::string shape =
      "base64:" +
      Base64Encode(std::vector<unsigned char>(obj.begin(), obj.end())) +
      ":cube.obj";
  const std::string xml =
      Replace(kTemplate, "<Frame><guid>f0</guid>",
              "<Frame><guid>f0</guid><shape>" + shape + "</shape>");
  EXPECT_THAT(ErrorOf(xml, "/nonexistent"),
              StartsWith(At(xml, "<shape>") + kModulePath +
                         "/frames/Frame[1]/shape: embedded mesh 'cube.obj': "
                         "MuJoCo cannot read it: "));
  EXPECT_THAT(ErrorOf(xml, "/nonexistent"), HasSubstr("cube.obj"));
}

TEST(ScenarioXml, MissingFileNamesThePath) {
  try {
    ReadScenarioFile("/nonexistent/dir/s.xml");
    FAIL() << "loaded a missing file";
  } catch (const ScenarioError& e) {
    EXPECT_THAT(e.what(), StartsWith("/nonexistent/dir/s.xml: cannot open "
                                     "the file (No such file"));
  }
}

TEST(ScenarioXml, AFolderGivenAsTheFileIsNamedAsOne) {
  try {
    ReadScenarioFile(::testing::TempDir());
    FAIL() << "loaded a folder";
  } catch (const ScenarioError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is a folder, not a scenario file"));
  }
}

// The checkpoint beside a scenario is a plausible wrong argument: it is
// named as what it is, with how to use it, not parsed as broken XML.
TEST(ScenarioXml, ACheckpointGivenAsTheScenarioIsNamedAsOne) {
  Scenario scenario;
  scenario.robots.push_back(MakeChain(ChainOptions{}));
  const std::string path = ::testing::TempDir() + "/run.checkpoint";
  SaveCheckpoint(path, Physics(scenario));
  try {
    ReadScenarioFile(path);
    FAIL() << "loaded a checkpoint as a scenario";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()),
              path +
                  ": is an mrsim-sim checkpoint, not a scenario; load it "
                  "with --load-checkpoint beside its scenario");
  }
}

// A Unity file (Y-up, left-handed) read into the Z-up model, using the
// template's frame f0 with a pose.
std::string UnityTemplate(const std::string& pose) {
  std::string xml =
      Replace(kTemplate, "frame=\"z-up\"", "frame=\"unity-y-up\"");
  // The lowered ground: Unity's up is y.
  xml = Replace(xml, "<x>0</x><y>0</y><z>-0.1</z>",
                "<x>0</x><y>-0.1</y><z>0</z>");
  return Replace(xml, "<Frame><guid>f0</guid>",
                 "<Frame><guid>f0</guid>" + pose);
}

Eigen::Matrix3d SwapYZ() {
  Eigen::Matrix3d s;
  s << 1, 0, 0, 0, 0, 1, 0, 1, 0;
  return s;
}

TEST(ScenarioXml, UnityFileIsConvertedToZUpOnRead) {
  const Eigen::Quaterniond qu = Eigen::Quaterniond(
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()));
  const std::string pose =
      "<scale><x>0.1</x><y>0.2</y><z>0.3</z></scale>"
      "<position><x>1</x><y>2</y><z>3</z></position>"
      "<rotation><x>10</x><y>20</y><z>30</z></rotation>"
      "<quatRotation><x>" +
      Num(qu.x()) + "</x><y>" + Num(qu.y()) + "</y><z>" + Num(qu.z()) +
      "</z><w>" + Num(qu.w()) + "</w></quatRotation>";
  const Scenario s = ReadScenarioString(UnityTemplate(pose), "t.xml", ".");
  const Frame& f = s.robots[0].modules[0].frames[0];
  EXPECT_EQ(f.position, Eigen::Vector3d(1, 3, 2));
  EXPECT_EQ(f.scale, Eigen::Vector3d(0.1, 0.3, 0.2));
  EXPECT_EQ(f.rotation, Eigen::Vector3d(-10, -30, -20));
  // The converted rotation does to converted vectors what Unity's did:
  // S * R_unity * v == R_zup * S * v.
  const Eigen::Matrix3d swap = SwapYZ();
  for (const Eigen::Vector3d& v :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
        Eigen::Vector3d(0.2, -0.7, 0.4)}) {
    EXPECT_TRUE(
        (swap * (qu * v)).isApprox(f.quat_rotation * (swap * v), 1e-12));
  }
  // Unity's Euler order (z, then x, then y about fixed axes) maps to
  // R = Rz(z) Rx(x) Ry(y) on the converted angles (docs/scenario.md).
  auto rad = [](double deg) { return deg * EIGEN_PI / 180; };
  using AA = Eigen::AngleAxisd;
  const Eigen::Matrix3d unity = (AA(rad(20), Eigen::Vector3d::UnitY()) *
                                 AA(rad(10), Eigen::Vector3d::UnitX()) *
                                 AA(rad(30), Eigen::Vector3d::UnitZ()))
                                    .toRotationMatrix();
  const Eigen::Vector3d e = f.rotation;
  const Eigen::Matrix3d zup = (AA(rad(e.z()), Eigen::Vector3d::UnitZ()) *
                               AA(rad(e.x()), Eigen::Vector3d::UnitX()) *
                               AA(rad(e.y()), Eigen::Vector3d::UnitY()))
                                  .toRotationMatrix();
  EXPECT_TRUE((swap * unity * swap).isApprox(zup, 1e-12));
  // Omitted fields mean the model's (Z-up) defaults, not swapped ones.
  EXPECT_EQ(s.settings.gravity, SimulationSettings().gravity);
  EXPECT_EQ(s.robots[0].sensor_modules[0].force_sensor->size,
            ForceSensor().size);
  EXPECT_EQ(s.robots[0].modules[0].frames[1].quat_rotation.coeffs(),
            Eigen::Quaterniond::Identity().coeffs());
}

TEST(ScenarioXml, UnityRoundTripKeepsEveryField) {
  const std::string dir = TempDir("scenario_unity_round_trip");
  std::ifstream png(SourcePath("scenarios/terrain.png"), std::ios::binary);
  std::ofstream(dir + "/terrain.png", std::ios::binary) << png.rdbuf();
  const Scenario s = EveryFieldScenario(WriteMesh(dir));
  const std::string unity = WriteScenarioString(s, FrameConvention::kUnityYUp);
  EXPECT_THAT(unity, HasSubstr("frame=\"unity-y-up\""));
  const Scenario back = ReadScenarioString(unity, "u.xml", dir);
  EXPECT_TRUE(back == s);
  EXPECT_EQ(WriteScenarioString(back, FrameConvention::kUnityYUp), unity);
  // In the Unity file gravity points along -y.
  EXPECT_THAT(unity,
              HasSubstr("<gravity>\n      <x>0</x>\n      <y>-1.62</y>"));
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

// scenarios/mrsim_original.xml as the original wrote it: Unity frame,
// centimetres, no frame attribute.
Scenario ReadOriginal() {
  ScenarioReadOptions options;
  options.frame = FrameConvention::kUnityYUp;
  options.length_scale = 0.01;
  return ReadScenarioFile(SourcePath("scenarios/mrsim_original.xml"), options);
}

// Read as native, an original file validated fine and was a robot a
// hundred times too big on its side; now it is refused with the way out.
TEST(ScenarioOriginal, ReadWithoutConvertingIsRefusedSayingHow) {
  const std::string path = SourcePath("scenarios/mrsim_original.xml");
  EXPECT_TRUE(IsOriginalMrsimFile(path));
  EXPECT_FALSE(IsOriginalMrsimFile(SourcePath("scenarios/case_study.xml")));
  try {
    ReadScenarioFile(path);
    ADD_FAILURE() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_THAT(e.what(), HasSubstr("mrsim_original.xml:2: Scenario/@frame"));
    EXPECT_THAT(e.what(), HasSubstr("convert --from unity-y-up"));
  }
  const Scenario s = ReadScenarioFile(path, kOriginalMrsimReadOptions);
  const Scenario same = ReadOriginal();
  EXPECT_EQ(WriteScenarioString(s), WriteScenarioString(same));
}

bool Near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).norm() < 1e-12;
}

TEST(ScenarioOriginal, FileTheOriginalWroteLoadsWithItsMeaning) {
  const Scenario s = ReadOriginal();
  ASSERT_EQ(s.robots.size(), 1u);
  const Robot& r = s.robots[0];
  EXPECT_EQ(r.name, "robot0");
  ASSERT_EQ(r.modules.size(), 4u);
  EXPECT_EQ(r.modules[1].axis, Axis::kYaw);
  // <scale>10</scale>: a uniform 10 cm box; Unity y (up) is our z.
  EXPECT_TRUE(
      Near(r.modules[0].frames[0].scale, Eigen::Vector3d::Constant(0.1)));
  // Lifted 5 mm onto the force plate under the sensor module.
  EXPECT_TRUE(Near(r.modules[1].position, Eigen::Vector3d(-0.2, 0, 0.055)));
  // The three placeholder locks became locks between neighbouring modules'
  // nearest frames.
  ASSERT_EQ(r.locks.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(r.locks[k].type, JointType::kLock);
    EXPECT_EQ(r.locks[k].left_frame_guid, r.modules[k].frames[1].guid);
    EXPECT_EQ(r.locks[k].right_frame_guid, r.modules[k + 1].frames[0].guid);
  }
  ASSERT_EQ(r.sensor_modules.size(), 1u);
  const SensorModule& sm = r.sensor_modules[0];
  EXPECT_FALSE(sm.force_sensor_lock.has_value());
  EXPECT_TRUE(sm.distance_sensor_locks.empty());
  ASSERT_TRUE(sm.force_sensor.has_value());
  EXPECT_TRUE(Near(sm.force_sensor->size, Eigen::Vector3d(0.08, 0.08, 0.005)));
  EXPECT_EQ(sm.force_sensor->rotation.coeffs(),
            Eigen::Quaterniond::Identity().coeffs());
  ASSERT_EQ(sm.distance_sensors.size(), 2u);
  for (const DistanceSensor& d : sm.distance_sensors) {
    EXPECT_EQ(d.quat_rotation.coeffs(),
              Eigen::Quaterniond::Identity().coeffs());
    EXPECT_NEAR(d.max_ray_distance, 2.0, 1e-12);
    EXPECT_NEAR(d.ray_resolution, 0.0005, 1e-15);  // 0.05 scene units
  }
  EXPECT_EQ(sm.distance_sensors[1].ray_direction, Eigen::Vector3d::UnitZ());
  // Lengths are scaled, gravity and masses are not; what the file leaves
  // out takes the model's defaults in metres.
  EXPECT_EQ(s.settings.gravity, SimulationSettings().gravity);
  EXPECT_EQ(r.modules[0].frames[0].mass, 0.05);
  EXPECT_NEAR(s.scene.height, 0.3, 1e-12);
  EXPECT_TRUE(Near(s.scene.position, Eigen::Vector3d(-1.6, -1.6, 0)));
  EXPECT_EQ(s.scene.meters_per_pixel, Scene().meters_per_pixel);
  EXPECT_EQ(r.modules[0].joint.velocity_gain, Joint().velocity_gain);
  ASSERT_EQ(s.scene_objects.size(), 2u);
  EXPECT_TRUE(Near(s.scene_objects[1].size, Eigen::Vector3d(0.1, 0.4, 0.1)));
  // Written in our layout it reads back the same.
  const std::string native = WriteScenarioString(s);
  EXPECT_TRUE(
      ReadScenarioString(native, "native.xml", SourcePath("scenarios")) == s);
}

TEST(ScenarioOriginal, EachOddityOfTheOriginalIsReadWithItsMeaning) {
  std::string xml = Replace(kTemplate,
                            "<scale><x>0.05</x><y>0.05</y><z>0.05"
                            "</z></scale>",
                            "<scale>0.04</scale>");
  xml = Replace(xml, "<guid>d0</guid>",
                "<guid>d0</guid><quatRotation><x>0</x><y>0</y><z>0</z><w>0</w>"
                "</quatRotation><ray_Resolution>0.05</ray_Resolution>");
  const std::string zero = "00000000-0000-0000-0000-000000000000";
  const std::string placeholder =
      "<guid>" + zero + "</guid><leftFrameGuid>" + zero +
      "</leftFrameGuid><rightFrameGuid>" + zero +
      "</rightFrameGuid><Kp>3</Kp><max_vel>0</max_vel>";
  xml = Replace(xml,
                "<forceSensorLock><guid>fl0</guid><leftFrameGuid>s0"
                "</leftFrameGuid><rightFrameGuid>fs0</rightFrameGuid><type>"
                "Lock</type></forceSensorLock>",
                "<forceSensorLock>" + placeholder + "</forceSensorLock>");
  xml = Replace(xml,
                "<scene><guid>scene</guid><position><x>0</x><y>0</y><z>-0.1</"
                "z></position></scene>",
                "<scene><guid>scene</guid><position><x>0</x><y>0</y><z>-0.1</"
                "z></position><vertices /><triangles />"
                "</scene>");
  // A real lock without <type> and with max_vel 0, as the original wrote.
  xml = Replace(xml, "<rightFrameGuid>s0</rightFrameGuid><type>Lock</type>",
                "<rightFrameGuid>s0</rightFrameGuid><max_vel>0</max_vel>");
  const Scenario s = ReadScenarioString(xml, "t.xml", ".");
  const Robot& r = s.robots[0];
  EXPECT_EQ(r.modules[0].frames[1].scale, Eigen::Vector3d::Constant(0.04));
  const DistanceSensor& d = r.sensor_modules[0].distance_sensors[0];
  EXPECT_EQ(d.quat_rotation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(d.ray_resolution, 0.05);
  EXPECT_FALSE(r.sensor_modules[0].force_sensor_lock.has_value());
  ASSERT_EQ(r.locks.size(), 1u);
  EXPECT_EQ(r.locks[0].type, JointType::kLock);
  EXPECT_EQ(r.locks[0].max_vel, 0);
  // A placeholder among a robot's locks: the default lock between the
  // modules it stood for (here one module, so nothing to add).
  const std::string with_placeholder = Replace(
      xml, "    </locks>", "<Joint>" + placeholder + "</Joint></locks>");
  EXPECT_EQ(
      ReadScenarioString(with_placeholder, "t.xml", ".").robots[0].locks.size(),
      1u);
  // A hinge still needs a speed; a mesh terrain is not modelled.
  const std::string still =
      Replace(xml, "<Kp>10</Kp>", "<Kp>10</Kp><max_vel>0</max_vel>");
  EXPECT_THAT(ErrorOf(still),
              StartsWith(At(still, "<max_vel>0</max_vel>") + kModulePath +
                         "/joint/max_vel: expected a positive "
                         "value for a hinge, got 0"));
  const std::string mesh =
      Replace(xml, "<vertices />", "<vertices><Vector3 /></vertices>");
  EXPECT_THAT(ErrorOf(mesh), StartsWith(At(mesh, "<vertices>") +
                                        "Scenario/scene/vertices: mrsim does "
                                        "not model the original's mesh "
                                        "terrain"));
}

// Replaces the n-th (1-based) occurrence of `from`.
std::string ReplaceNth(std::string text, const std::string& from,
                       const std::string& to, int n) {
  size_t at = std::string::npos;
  for (int i = 0; i < n; ++i) at = text.find(from, at + 1);
  EXPECT_NE(at, std::string::npos) << "no " << n << "th '" << from << "'";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(ScenarioOriginal, BrokenFieldInAnOriginalFileIsNamed) {
  const std::string original =
      ReadText(SourcePath("scenarios/mrsim_original.xml"));
  ScenarioReadOptions options;
  options.frame = FrameConvention::kUnityYUp;
  auto error = [&](const std::string& xml) -> std::string {
    try {
      ReadScenarioString(xml, "t.xml", SourcePath("scenarios"), options);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    ADD_FAILURE() << "loaded";
    return "";
  };
  std::string xml = ReplaceNth(original, "<Kp>3</Kp>", "<Kp>fast</Kp>", 3);
  EXPECT_THAT(error(xml), StartsWith(At(xml, "<Kp>fast") +
                                     "Scenario/robot[1]/modules/Module[3]/"
                                     "joint/Kp: expected a number, got "
                                     "'fast'"));
  xml = ReplaceNth(original, "<scale>10</scale>", "<scale>ten</scale>", 2);
  EXPECT_THAT(error(xml), StartsWith(At(xml, "<scale>ten") +
                                     "Scenario/robot[1]/modules/Module[1]/"
                                     "frames/Frame[2]/scale: expected a "
                                     "number, got 'ten'"));
  xml =
      ReplaceNth(original, "0.05</ray_Resolution>", "fine</ray_Resolution>", 2);
  EXPECT_THAT(error(xml),
              StartsWith(At(xml, "fine</ray") +
                         "Scenario/robot[1]/sensorModules/SensorModule[1]/"
                         "distanceSensors/DistanceSensor[2]/ray_Resolution: "
                         "expected a number, got 'fine'"));
  // A frame that says z-up cannot be read as Unity's.
  EXPECT_THAT(
      error(Replace(original, "<Scenario ", "<Scenario frame=\"z-up\" ")),
      HasSubstr("Scenario/@frame: the file says frame=\"z-up\" but "
                "it was read as unity-y-up"));
}

}  // namespace
}  // namespace mrsim

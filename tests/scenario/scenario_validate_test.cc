// One validator: every rule the MJCF builder and the physics used to
// enforce on their own is refused, with the same element path, by the file
// reader (file:line: path) and by BuildMjcf and Physics on a scenario built
// in memory; and what validates builds.
#include "sim_core/scenario/scenario_validate.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;
using testing::SourcePath;
using ::testing::StartsWith;
using testing::TempDir;

// A valid scenario with every kind of part the builder looks at: a chain
// with a sensor module (force plate and ray), a ball, a height field and
// two loose frames joined by a hinge.
Scenario Base(const std::string& dir) {
  std::ifstream png(SourcePath("scenarios/terrain.png"), std::ios::binary);
  std::ofstream(dir + "/terrain.png", std::ios::binary) << png.rdbuf();
  ChainOptions options;
  options.name = "r";
  options.modules = 2;
  options.sensor_after = {-1};
  options.force_sensors = true;
  options.front_distance_sensor = true;
  options.origin = Eigen::Vector3d(0, 0, 0.1);
  Scenario s;
  s.base_dir = dir;
  s.robots.push_back(MakeChain(options));
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.position = Eigen::Vector3d(0.5, 0, 0.2);
  s.scene_objects.push_back(ball);
  s.scene.guid = "ground";
  s.scene.height_image = "terrain.png";
  s.scene.height = 0.3;
  s.scene.position = Eigen::Vector3d(-1.6, -1.6, 0);
  for (int f = 0; f < 2; ++f) {
    Frame frame;
    frame.guid = "loose" + std::to_string(f);
    frame.position = Eigen::Vector3d(1, 0.05 * f, 0.3);
    s.loose_frames.push_back(frame);
  }
  Joint hinge;
  hinge.guid = "loose hinge";
  hinge.left_frame_guid = "loose0";
  hinge.right_frame_guid = "loose1";
  s.loose_joints.push_back(hinge);
  return s;
}

struct Rule {
  std::string name;
  std::function<void(Scenario&)> break_it;
  std::string path;
  std::string message;
};

const char kM1[] = "Scenario/robot[1]/modules/Module[1]";
const char kSm1[] = "Scenario/robot[1]/sensorModules/SensorModule[1]";

std::vector<Rule> BuilderRules() {
  const std::string m1 = kM1, sm1 = kSm1;
  return {
      {"static frame of mass 0",
       [](Scenario& s) {
         Frame& f = s.robots[0].modules[0].frames[0];
         f.is_static = true;
         f.mass = 0;
       },
       m1 + "/frames/Frame[1]/mass", "expected a positive value, got 0"},
      {"box scale not positive",
       [](Scenario& s) { s.robots[0].modules[0].frames[1].scale.y() = 0; },
       m1 + "/frames/Frame[2]/scale", "expected positive x, y, z"},
      {"robot part in the ground",
       [](Scenario& s) {
         s.robots[0].modules[0].frames[1].position.z() = s.scene.position.z();
       },
       m1 + "/frames/Frame[2]/position", "mm below the ground"},
      {"force plate in the ground",
       [](Scenario& s) {
         // The ground 0.5 mm under the module bottoms: only the 2 mm plate
         // (outside its module, under it) reaches 1.5 mm into it.
         const SensorModule& sm = s.robots[0].sensor_modules[0];
         s.scene.position.z() = sm.position.z() - sm.size.z() / 2 - 0.0005;
       },
       sm1 + "/position", "its force plate"},
      {"force plate face",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].force_sensor->sensor_position = 4;
       },
       sm1 + "/forceSensor/sensorPosition", "expected 0..3"},
      {"force plate mass",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].force_sensor->mass = 0;
       },
       sm1 + "/forceSensor/mass", "expected a positive value"},
      {"force plate size",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].force_sensor->size.z() = -0.001;
       },
       sm1 + "/forceSensor/size", "expected positive x, y, z"},
      {"distance sensor face",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].distance_sensors[0].sensor_position = 6;
       },
       sm1 + "/distanceSensors/DistanceSensor[1]/sensorPosition",
       "expected 0..5"},
      {"sensor module mass",
       [](Scenario& s) { s.robots[0].sensor_modules[0].mass = 0; },
       sm1 + "/mass", "expected a positive value"},
      {"camera wider than a picture may be",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].cameras.emplace_back().width = 4000;
       },
       sm1 + "/cameras/Camera[1]/width", "expected 16..640"},
      {"camera frame rate zero",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].cameras.emplace_back().rate = 0;
       },
       sm1 + "/cameras/Camera[1]/rate", "expected a positive value"},
      {"camera field of view",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].cameras.emplace_back().fovy = 180;
       },
       sm1 + "/cameras/Camera[1]/fovy", "expected 1..170"},
      {"camera far before near",
       [](Scenario& s) {
         Camera& c = s.robots[0].sensor_modules[0].cameras.emplace_back();
         c.near_clip = 0.5;
         c.far_clip = 0.2;
       },
       sm1 + "/cameras/Camera[1]/far", "must be beyond near"},
      {"sensor module size",
       [](Scenario& s) { s.robots[0].sensor_modules[0].size.x() = -1; },
       sm1 + "/size", "expected positive x, y, z"},
      {"guid used twice in a robot",
       [](Scenario& s) {
         Module& m = s.robots[0].modules[1];
         m.frames[1].guid = s.robots[0].modules[0].frames[0].guid;
       },
       "Scenario/robot[1]/modules/Module[2]/frames/Frame[2]/guid",
       "duplicate guid 'r/m0/f0'"},
      {"lower limit above upper",
       [](Scenario& s) {
         s.robots[0].modules[0].joint.lower_range_limit = 2;
         s.robots[0].modules[0].joint.upper_range_limit = 1;
       },
       m1 + "/joint/lowerRangeLimit", "lower limit 2 is above the upper limit"},
      {"lock naming an unknown part",
       [](Scenario& s) { s.robots[0].locks[0].right_frame_guid = "nowhere"; },
       "Scenario/robot[1]/locks/Joint[1]/rightFrameGuid",
       "no frame or sensor module with guid 'nowhere' in robot 'r'"},
      {"lock naming a sensor",
       [](Scenario& s) {
         s.robots[0].locks[0].right_frame_guid =
             s.robots[0].sensor_modules[0].force_sensor->guid;
       },
       "Scenario/robot[1]/locks/Joint[1]/rightFrameGuid",
       "it is not a part this joint can join"},
      {"hinges closing a loop",
       [](Scenario& s) {
         Joint extra;
         extra.guid = "extra";
         extra.left_frame_guid = s.robots[0].modules[0].frames[0].guid;
         extra.right_frame_guid = s.robots[0].modules[0].frames[1].guid;
         s.robots[0].locks.push_back(extra);
       },
       "Scenario/robot[1]/locks/Joint[3]", "hinge 'extra' closes a loop"},
      {"scene object size",
       [](Scenario& s) { s.scene_objects[0].size.z() = 0; },
       "Scenario/sceneObjects/SceneObject[1]/size",
       "expected positive x, y, z"},
      {"scene object camera face",
       [](Scenario& s) {
         s.scene_objects[0].cameras.emplace_back().sensor_position = 6;
       },
       "Scenario/sceneObjects/SceneObject[1]/cameras/Camera[1]/sensorPosition",
       "expected 0..5"},
      {"scene object camera taller than a picture may be",
       [](Scenario& s) {
         s.scene_objects[0].cameras.emplace_back().height = 960;
       },
       "Scenario/sceneObjects/SceneObject[1]/cameras/Camera[1]/height",
       "expected 16..480"},
      {"scene object camera faster than 120 pictures a second",
       [](Scenario& s) {
         s.scene_objects[0].cameras.emplace_back().rate = 500;
       },
       "Scenario/sceneObjects/SceneObject[1]/cameras/Camera[1]/rate",
       "expected"},
      {"loose sensor module camera far before near",
       [](Scenario& s) {
         SensorModule sm;
         sm.guid = "loose eye";
         sm.position = Eigen::Vector3d(1, 0.5, 0.3);
         Camera& c = sm.cameras.emplace_back();
         c.near_clip = 2;
         c.far_clip = 1;
         s.loose_sensor_modules.push_back(sm);
       },
       "Scenario/sensorModules/SensorModule[1]/cameras/Camera[1]/far",
       "must be beyond near"},
      {"a robot named as the scene objects' cameras' owner",
       [](Scenario& s) { s.robots[0].name = "scene"; },
       "Scenario/robot[1]/name", "names the scenario's scene objects"},
      {"moving scene object of mass 0",
       [](Scenario& s) { s.scene_objects[0].mass = 0; },
       "Scenario/sceneObjects/SceneObject[1]/mass",
       "expected a positive value, got 0"},
      {"terrain pixel size", [](Scenario& s) { s.scene.meters_per_pixel = 0; },
       "Scenario/scene/metersPerPixel", "expected a positive value"},
      {"terrain height", [](Scenario& s) { s.scene.height = -0.1; },
       "Scenario/scene/height", "expected a value >= 0"},
      {"two robots of one name",
       [](Scenario& s) {
         ChainOptions o;
         o.name = "q";
         o.modules = 1;
         o.origin = Eigen::Vector3d(0, 0.5, 0.1);
         s.robots.push_back(MakeChain(o));
         s.robots.back().name = "r";
       },
       "Scenario/robot[2]/name", "duplicate robot name 'r'"},
      {"unreadable mesh",
       [](Scenario& s) { s.robots[0].modules[0].frames[0].shape = "no.obj"; },
       m1 + "/frames/Frame[1]/shape", "cannot read mesh file"},
      {"unreadable height image",
       [](Scenario& s) { s.scene.height_image = "missing.png"; },
       "Scenario/scene/height_Image", "cannot read the height image"},
      // Physical bounds (scenario_schema.h): beyond them MuJoCo's
      // arithmetic overflows and the simulator stood still at time 0.
      {"frame position beyond the world",
       [](Scenario& s) {
         s.robots[0].modules[0].frames[0].position.x() = -1e308;
       },
       m1 + "/frames/Frame[1]/position",
       "expected x, y, z within -10000..10000, got (-1e+308"},
      {"frame mass beyond the bound",
       [](Scenario& s) { s.robots[0].modules[0].frames[0].mass = 1e308; },
       m1 + "/frames/Frame[1]/mass", "expected a value within"},
      {"frame scale beyond the bound",
       [](Scenario& s) { s.robots[0].modules[0].frames[1].scale.y() = 1e12; },
       m1 + "/frames/Frame[2]/scale", "expected x, y, z within"},
      {"scene object position beyond the world",
       [](Scenario& s) { s.scene_objects[0].position.z() = 1e308; },
       "Scenario/sceneObjects/SceneObject[1]/position",
       "expected x, y, z within"},
      {"sensor module rotation beyond every bound",
       [](Scenario& s) {
         s.robots[0].sensor_modules[0].quat_rotation.w() = 1e300;
       },
       sm1 + "/quatRotation", "expected x, y, z, w within"},
      {"servo gain beyond every bound",
       [](Scenario& s) { s.robots[0].modules[1].joint.kp = 1e308; },
       "Scenario/robot[1]/modules/Module[2]/joint/Kp",
       "expected a value within"},
      {"a timestep that never advances",
       [](Scenario& s) { s.settings.timestep = 1e-300; },
       "Scenario/settings/timestep", "expected 1e-06..1"},
      {"a servo on a module's hinge, which always has one",
       [](Scenario& s) { s.robots[0].modules[0].joint.servo = true; },
       m1 + "/joint/servo", "only a loose hinge (Scenario/joints/Joint)"},
      {"a servo on a loose lock",
       [](Scenario& s) {
         s.loose_joints[0].type = JointType::kLock;
         s.loose_joints[0].servo = true;
       },
       "Scenario/joints/Joint[1]/servo", "a Lock does not turn"},
      {"a loose servo without torque",
       [](Scenario& s) {
         s.loose_joints[0].servo = true;
         s.loose_joints[0].max_torque = 0;
       },
       "Scenario/joints/Joint[1]/maxTorque", "expected a positive value"},
      {"loose joint naming a scene object",
       [](Scenario& s) { s.loose_joints[0].right_frame_guid = "ball"; },
       "Scenario/joints/Joint[1]/rightFrameGuid",
       "no frame or sensor module with guid 'ball' among the loose parts"},
  };
}

std::string LineOf(const std::string& path, int line) {
  std::ifstream in(path);
  std::string text;
  for (int i = 0; i < line && std::getline(in, text); ++i) {
  }
  return text;
}

TEST(ScenarioValidate, TheBaseScenarioValidatesBuildsAndLoads) {
  const std::string dir = TempDir("validate_base");
  const Scenario s = Base(dir);
  EXPECT_NO_THROW(ValidateScenario(s));
  EXPECT_NO_THROW(BuildMjcf(s));
  EXPECT_NO_THROW(Physics physics(s));
  WriteScenarioFile(s, dir + "/base.xml");
  EXPECT_TRUE(ReadScenarioFile(dir + "/base.xml") == s);
}

TEST(ScenarioValidate, EveryBuilderRuleIsRefusedByTheReaderBuilderAndPhysics) {
  const std::string dir = TempDir("validate_rules");
  for (const Rule& rule : BuilderRules()) {
    SCOPED_TRACE(rule.name);
    Scenario s = Base(dir);
    rule.break_it(s);
    // In memory: the builder and the physics refuse it with the path.
    try {
      BuildMjcf(s);
      ADD_FAILURE() << "BuildMjcf accepted it";
    } catch (const ScenarioError& e) {
      EXPECT_EQ(e.path(), rule.path) << e.what();
      EXPECT_THAT(e.message(), HasSubstr(rule.message));
      EXPECT_THAT(e.what(), StartsWith(rule.path + ": "));
    }
    EXPECT_THROW(Physics physics(s), ScenarioError);
    // In a file: the reader refuses it with file:line: path.
    const std::string file = dir + "/broken.xml";
    WriteScenarioFile(s, file);
    try {
      ReadScenarioFile(file);
      ADD_FAILURE() << "the reader accepted it";
    } catch (const ScenarioError& e) {
      EXPECT_THAT(e.what(), StartsWith(file + ":" + std::to_string(e.line()) +
                                       ": " + rule.path + ": "));
      EXPECT_THAT(e.message(), HasSubstr(rule.message));
      // The line is that of the element the path ends in.
      std::string leaf = rule.path.substr(rule.path.rfind('/') + 1);
      leaf = leaf.substr(0, leaf.find('['));
      EXPECT_THAT(LineOf(file, e.line()), HasSubstr("<" + leaf + ">"));
    }
  }
}

// A ray that starts inside another part of its robot reads about 0 the
// whole run: told as a warning at the sensor's face, never refused, since
// files the original MRSim ran hold such rays (its Appendix F).
// A camera on a face turned to a neighbour sees only that neighbour.
TEST(ScenarioValidate, ACameraLookingIntoItsOwnRobotIsAWarning) {
  const std::string dir = TempDir("validate_camera_warning");
  Scenario s = Base(dir);
  Camera& c = s.robots[0].sensor_modules[0].cameras.emplace_back();
  c.sensor_position = 4;  // the front: looks out
  EXPECT_TRUE(ScenarioWarnings(s).empty());
  c.sensor_position = 5;  // the back: module 0
  EXPECT_NO_THROW(ValidateScenario(s));
  const std::vector<ScenarioWarning> warnings = ScenarioWarnings(s);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].path,
            std::string(kSm1) + "/cameras/Camera[1]/sensorPosition");
  EXPECT_THAT(warnings[0].message,
              HasSubstr("the camera on face 5 (back) looks straight into "
                        "'r/m0/f0', so it would see only that"));
}

// The same for a loose sensor module turned to a loose part beside it; a
// scene object's camera, on the box around it, looks out.
TEST(ScenarioValidate, ALooseCameraLookingIntoALoosePartIsAWarning) {
  const std::string dir = TempDir("validate_loose_camera_warning");
  Scenario s = Base(dir);
  SensorModule sm;
  sm.guid = "loose eye";
  // Just in front (+x) of the loose frame 'loose0' at (1, 0, 0.3).
  sm.position = Eigen::Vector3d(1.05, 0, 0.3);
  Camera& c = sm.cameras.emplace_back();
  c.sensor_position = 4;  // the front: looks out
  s.loose_sensor_modules.push_back(sm);
  s.scene_objects[0].cameras.emplace_back().sensor_position = 5;
  EXPECT_TRUE(ScenarioWarnings(s).empty());
  s.loose_sensor_modules[0].cameras[0].sensor_position = 5;  // the back
  const std::vector<ScenarioWarning> warnings = ScenarioWarnings(s);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].path,
            "Scenario/sensorModules/SensorModule[1]/cameras/Camera[1]/"
            "sensorPosition");
  EXPECT_THAT(warnings[0].message,
              HasSubstr("the camera on face 5 (back) looks straight into "
                        "'loose0', so it would see only that loose part"));
}

TEST(ScenarioValidate, ARayRunningIntoTheRobotIsAWarningNotARefusal) {
  const std::string dir = TempDir("validate_ray_warning");
  const std::string sm1 = "Scenario/robot[1]/sensorModules/SensorModule[1]";
  const std::vector<std::pair<std::function<void(Scenario&)>, std::string>>
      cases = {
          // The back face of the front sensor module touches module 0.
          {[](Scenario& s) {
             DistanceSensor& d =
                 s.robots[0].sensor_modules[0].distance_sensors[0];
             d.sensor_position = 5;
             d.ray_direction = -Eigen::Vector3d::UnitX();
           },
           "the ray of face 5 (back) runs into 'r/m0/f0' as it leaves its "
           "sensor module, so it would read about 0"},
          // Face 4 (front) looking back: through the sensor module (which
          // the ray skips) straight into module 0 behind it.
          {[](Scenario& s) {
             s.robots[0].sensor_modules[0].distance_sensors[0].ray_direction =
                 -Eigen::Vector3d::UnitX();
           },
           "the ray of face 4 (front) runs into 'r/m0/f0' as it leaves its "
           "sensor module"}};
  EXPECT_TRUE(ScenarioWarnings(Base(dir)).empty());
  for (const auto& [break_it, message] : cases) {
    SCOPED_TRACE(message);
    Scenario s = Base(dir);
    break_it(s);
    EXPECT_NO_THROW(ValidateScenario(s));
    EXPECT_NO_THROW(Physics physics(s));
    const std::string file = dir + "/ray.xml";
    WriteScenarioFile(s, file);
    ScenarioSource source;
    ScenarioReadOptions read;
    read.source_out = &source;
    const Scenario back = ReadScenarioFile(file, read);
    const std::vector<ScenarioWarning> warnings =
        ScenarioWarnings(back, &source);
    ASSERT_EQ(warnings.size(), 1u);
    const std::string path =
        sm1 + "/distanceSensors/DistanceSensor[1]/" + "sensorPosition";
    EXPECT_EQ(warnings[0].path, path);
    EXPECT_THAT(warnings[0].message, HasSubstr(message));
    EXPECT_THAT(warnings[0].text,
                StartsWith(file + ":" + std::to_string(source.LineOf(path)) +
                           ": " + path + ": warning: "));
  }
}

// Scenarios built in memory (genomes, the studio) can hold what no file
// can: NaN. Every number field refuses it by its bound.
TEST(ScenarioValidate, NanInAnyNumberIsRefusedNamingTheField) {
  const std::string dir = TempDir("validate_nan");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::function<void(Scenario&)>, std::string>>
      cases = {
          {[&](Scenario& s) { s.robots[0].modules[0].position.y() = nan; },
           std::string(kM1) + "/position"},
          {[&](Scenario& s) { s.robots[0].modules[0].frames[0].mass = nan; },
           std::string(kM1) + "/frames/Frame[1]/mass"},
          {[&](Scenario& s) { s.robots[0].modules[0].joint.max_vel = nan; },
           std::string(kM1) + "/joint/max_vel"},
          {[&](Scenario& s) { s.settings.gravity.z() = nan; },
           "Scenario/settings/gravity"},
          {[&](Scenario& s) { s.scene_objects[0].quat_rotation.x() = nan; },
           "Scenario/sceneObjects/SceneObject[1]/quatRotation"},
      };
  for (const auto& [break_it, path] : cases) {
    SCOPED_TRACE(path);
    Scenario s = Base(dir);
    break_it(s);
    try {
      ValidateScenario(s);
      ADD_FAILURE() << "accepted";
    } catch (const ScenarioError& e) {
      EXPECT_EQ(e.path(), path) << e.what();
    }
  }
}

}  // namespace
}  // namespace mrsim

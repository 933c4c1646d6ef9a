// The schema table: what the inspector relies on (fields by part kind, text
// in and out with the schema's messages, units, limits, defaults) and what
// frame and unit conversion take from it.
#include "sim_core/scenario/scenario_schema.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario.h"
#include "sim_core/scenario_tool/schema_table.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/scenario/sensor_face.h"

namespace mrsim {
namespace {

using ::testing::ElementsAre;
using ::testing::EndsWith;

const FieldSpec* SpecOf(PartKind kind, const std::string& xml) {
  for (const FieldSpec& f : FieldSpecsOf(kind)) {
    if (f.info.xml == xml) return &f;
  }
  return nullptr;
}

template <typename P>
FieldRef FieldOf(P& part, const std::string& xml) {
  for (const FieldRef& f : FieldsOf(part)) {
    if (f.info().xml == xml) return f;
  }
  ADD_FAILURE() << "no field " << xml;
  return FieldsOf(part).front();
}

// The message SetText gives for `text`, or "" when it is accepted.
std::string SetTextError(const FieldRef& f, const std::string& text) {
  try {
    f.SetText(text);
  } catch (const FieldError& e) {
    return e.what();
  }
  return "";
}

// A part kind added to the list but never described (no fields, no
// children, held by no part) would be a kind no file can hold and the
// schema document would not mention: each kind must be reachable from the
// scenario and have its own section in `mrsim-scenario schema`.
TEST(ScenarioSchema, EveryPartKindIsDescribedAndInTheSchemaTable) {
  std::set<PartKind> reached{PartKind::kScenario};
  std::vector<PartKind> todo{PartKind::kScenario};
  while (!todo.empty()) {
    const PartKind kind = todo.back();
    todo.pop_back();
    for (const ChildSpec& c : ChildSpecsOf(kind)) {
      if (reached.insert(c.kind).second) todo.push_back(c.kind);
    }
  }
  const std::string table = SchemaMarkdown();
  std::set<std::string> names;
  ASSERT_FALSE(AllPartKinds().empty());
  for (const PartKind kind : AllPartKinds()) {
    const std::string name = ToString(kind);
    SCOPED_TRACE(name);
    EXPECT_TRUE(names.insert(name).second) << "two kinds are called " << name;
    EXPECT_FALSE(FieldSpecsOf(kind).empty() && ChildSpecsOf(kind).empty())
        << "a part kind with no fields and no children";
    EXPECT_TRUE(reached.count(kind)) << "no part holds a " << name;
    EXPECT_NE(table.find("### " + name + "\n"), std::string::npos)
        << "not in the schema table";
  }
  EXPECT_EQ(reached.size(), AllPartKinds().size());
}

TEST(ScenarioSchema, JointFieldsCarryUnitsDefaultsAndLimits) {
  const FieldSpec* gain = SpecOf(PartKind::kJoint, "velocityGain");
  ASSERT_NE(gain, nullptr);
  EXPECT_STREQ(gain->info.member, "velocity_gain");
  EXPECT_STREQ(gain->info.unit, "N m s/rad");
  EXPECT_EQ(gain->default_text, "5");
  EXPECT_EQ(gain->type, FieldType::kNumber);
  const FieldSpec* torque = SpecOf(PartKind::kJoint, "maxTorque");
  ASSERT_NE(torque, nullptr);
  EXPECT_STREQ(torque->info.unit, "N m");
  EXPECT_EQ(torque->default_text, "2");
  const FieldSpec* brk = SpecOf(PartKind::kJoint, "breakForce");
  ASSERT_NE(brk, nullptr);
  EXPECT_STREQ(brk->info.unit, "N");
  EXPECT_EQ(brk->default_text, "0");
  EXPECT_FALSE(brk->info.required);
  const FieldSpec* type = SpecOf(PartKind::kJoint, "type");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->type, FieldType::kChoice);
  EXPECT_THAT(type->choices, ElementsAre("Hinge", "Lock"));
  EXPECT_NE(std::string(SpecOf(PartKind::kFrame, "mass")->info.help), "");
  const FieldSpec* resolution =
      SpecOf(PartKind::kDistanceSensor, "ray_Resolution");
  ASSERT_NE(resolution, nullptr);
  EXPECT_EQ(resolution->type, FieldType::kNumber);
}

TEST(ScenarioSchema, FieldsAreListedInFileOrder) {
  std::vector<std::string> names;
  for (const FieldSpec& f : FieldSpecsOf(PartKind::kFrame)) {
    names.push_back(f.info.xml);
  }
  EXPECT_THAT(names,
              ElementsAre("guid", "shape", "scale", "position", "rotation",
                          "quatRotation", "mass", "isStatic", "materialName"));
  const auto& children = ChildSpecsOf(PartKind::kModule);
  ASSERT_EQ(children.size(), 2u);
  EXPECT_STREQ(children[0].info.xml, "frames");
  EXPECT_EQ(children[0].count, ChildCount::kArray);
  EXPECT_EQ(children[0].kind, PartKind::kFrame);
  EXPECT_STREQ(children[1].info.xml, "joint");
  EXPECT_EQ(children[1].kind, PartKind::kJoint);
}

TEST(ScenarioSchema, SetTextParsesChecksLimitsAndKeepsTheValueOnError) {
  Joint joint;
  const FieldRef kp = FieldOf(joint, "Kp");
  EXPECT_EQ(SetTextError(kp, "fast"), "expected a number, got 'fast'");
  EXPECT_EQ(SetTextError(kp, "-1"), "expected a value >= 0, got -1");
  EXPECT_EQ(joint.kp, Joint().kp);
  EXPECT_EQ(SetTextError(kp, "12.5"), "");
  EXPECT_EQ(joint.kp, 12.5);
  EXPECT_EQ(kp.GetText(), "12.5");

  Frame frame;
  const FieldRef scale = FieldOf(frame, "scale");
  EXPECT_EQ(scale.type(), FieldType::kVector);
  EXPECT_EQ(SetTextError(scale, "0 1 1"),
            "expected positive x, y, z, got (0, 1, 1)");
  EXPECT_EQ(SetTextError(scale, "0.1 0.2"),
            "expected 3 numbers x y z, got '0.1 0.2'");
  EXPECT_EQ(SetTextError(scale, "0.1 0.2 0.3"), "");
  EXPECT_EQ(frame.scale, Eigen::Vector3d(0.1, 0.2, 0.3));

  Module module;
  const FieldRef axis = FieldOf(module, "axis");
  EXPECT_THAT(axis.choices(), ElementsAre("Pitch", "Yaw"));
  EXPECT_EQ(SetTextError(axis, "Roll"), "expected Pitch or Yaw, got 'Roll'");
  EXPECT_EQ(SetTextError(axis, "Yaw"), "");
  EXPECT_EQ(module.axis, Axis::kYaw);

  ForceSensor plate;
  EXPECT_EQ(SetTextError(FieldOf(plate, "sensorPosition"), "4"),
            "expected 0..3 (bottom, left, top, right), got 4");
  SceneObject object;
  EXPECT_EQ(SetTextError(FieldOf(object, "shape"), "Cone"),
            "expected Box, Sphere, Cylinder or Capsule, got 'Cone'");
  EXPECT_EQ(SetTextError(FieldOf(object, "quatRotation"), "0 0 0 0"),
            "expected a rotation quaternion, got all zeros");
}

TEST(ScenarioSchema, GetTextThenSetTextGivesTheSameValue) {
  ChainOptions options;
  options.sensor_after = {-1};
  options.force_sensors = true;
  options.front_distance_sensor = true;
  Robot robot = MakeChain(options);
  Frame& frame = robot.modules[0].frames[0];
  frame.position = Eigen::Vector3d(0.1 + 0.2, -1.0 / 3, 1e-17);
  frame.quat_rotation = Eigen::Quaterniond(
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  frame.material_name = "rubber & <steel>";
  Frame copy;
  const auto from = FieldsOf(frame);
  const auto to = FieldsOf(copy);
  ASSERT_EQ(from.size(), to.size());
  for (size_t i = 0; i < from.size(); ++i) {
    SCOPED_TRACE(from[i].info().xml);
    to[i].SetText(from[i].GetText());
  }
  EXPECT_TRUE(copy == frame);
  DistanceSensor& ray = robot.sensor_modules[0].distance_sensors[0];
  ray.ray_resolution = 0.05;
  DistanceSensor ray_copy;
  const auto ray_from = FieldsOf(ray);
  const auto ray_to = FieldsOf(ray_copy);
  for (size_t i = 0; i < ray_from.size(); ++i) {
    ray_to[i].SetText(ray_from[i].GetText());
  }
  EXPECT_TRUE(ray_copy == ray);
}

TEST(ScenarioSchema, FileErrorsUseTheSchemasMessage) {
  const std::string xml = R"(<Scenario><sceneObjects><SceneObject>
<guid>ball</guid><shape>Sphere</shape><size><x>0.1</x><y>-1</y><z>0.1</z></size>
</SceneObject></sceneObjects></Scenario>)";
  SceneObject object;
  const std::string message =
      SetTextError(FieldOf(object, "size"), "0.1 -1 0.1");
  ASSERT_NE(message, "");
  try {
    ReadScenarioString(xml, "t.xml", ".");
    FAIL() << "loaded";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()),
              "t.xml:2: Scenario/sceneObjects/SceneObject[1]/size: " + message);
    EXPECT_EQ(e.path(), "Scenario/sceneObjects/SceneObject[1]/size");
    EXPECT_EQ(e.message(), message);
    EXPECT_EQ(e.line(), 2);
  }
}

TEST(ScenarioSchema, ScaleLengthsScalesLengthsButNotGravityOrMasses) {
  Scenario s;
  ChainOptions options;
  options.sensor_after = {-1};
  options.front_distance_sensor = true;
  s.robots.push_back(MakeChain(options));
  s.scene.height = 0.3;
  FluidRegion water;
  water.velocity = Eigen::Vector3d(0.1, 0, 0);
  s.fluid_regions.push_back(water);
  Scenario scaled = s;
  ScaleLengths(&scaled, 100);
  EXPECT_EQ(scaled.settings.gravity, s.settings.gravity);
  EXPECT_EQ(scaled.robots[0].modules[0].frames[0].mass,
            s.robots[0].modules[0].frames[0].mass);
  EXPECT_EQ(scaled.robots[0].modules[0].frames[0].scale,
            100 * s.robots[0].modules[0].frames[0].scale);
  EXPECT_EQ(scaled.robots[0].modules[2].position,
            100 * s.robots[0].modules[2].position);
  const DistanceSensor& ray = s.robots[0].sensor_modules[0].distance_sensors[0];
  const DistanceSensor& scaled_ray =
      scaled.robots[0].sensor_modules[0].distance_sensors[0];
  EXPECT_EQ(scaled_ray.max_ray_distance, 100 * ray.max_ray_distance);
  EXPECT_EQ(scaled_ray.ray_direction, ray.ray_direction);
  EXPECT_EQ(scaled.scene.height, 30);
  EXPECT_EQ(scaled.scene.meters_per_pixel, 100 * s.scene.meters_per_pixel);
  EXPECT_EQ(scaled.fluid_regions[0].velocity, Eigen::Vector3d(10, 0, 0));
  EXPECT_EQ(scaled.fluid_regions[0].density, water.density);
}

// The faces' names are one list: the schema's value names are it.
TEST(ScenarioSchema, FaceNamesAreTheOneListOfSensorFaces) {
  std::string all;
  for (const char* name : kSensorFaceNames) {
    all += (all.empty() ? "" : ", ") + std::string(name);
  }
  EXPECT_EQ(all, kSensorFaceList);
  EXPECT_EQ(all.rfind(kForcePlateFaceList, 0), 0u);
  EXPECT_EQ(std::string(kForcePlateFaceList), "bottom, left, top, right");
}

}  // namespace
}  // namespace mrsim

// The studio's editing model without a window: commands, undo/redo, the
// validator, and equality with what `mrsim-scenario new` writes.
#include "studio/design/design.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/mesh/triangle_mesh.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/face_geometry.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/chain_edit.h"
#include "studio/design/inspector_fields.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

using ::testing::HasSubstr;

using mrsim::testing::BinaryPath;
using mrsim::testing::ChildProcess;
using mrsim::testing::SourcePath;
using mrsim::testing::TempDir;

std::string Bytes(const Design& d) { return WriteScenarioString(d.scenario()); }

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs mrsim-scenario new with `args` and returns the file it wrote.
std::string ScenarioNew(const std::vector<std::string>& args,
                        const std::string& dir) {
  const std::string out = dir + "/new.xml";
  std::vector<std::string> argv = {
      BinaryPath("sim_core/scenario_tool/mrsim-scenario"), "new"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.push_back("-o");
  argv.push_back(out);
  ChildProcess tool(argv, dir + "/tool.log");
  EXPECT_EQ(tool.Wait(60), 0) << tool.Output();
  return out;
}

TEST(StudioDesign, EveryEditUndoesAndRedoesToIdenticalBytes) {
  Design d;
  const Selection module1{SelectionKind::kModule, 0, 1};
  const std::vector<std::pair<std::string, std::function<void()>>> edits = {
      {"add pitch", [&] { d.AddPart(NextPart::kPitchModule); }},
      {"add yaw", [&] { d.AddPart(NextPart::kYawModule); }},
      {"add sensor", [&] { d.AddPart(NextPart::kSensorModule); }},
      {"add pitch 2", [&] { d.AddPart(NextPart::kPitchModule); }},
      {"select+insert",
       [&] {
         d.Select(module1);
         d.AddPart(NextPart::kYawModule);
       }},
      {"move back", [&] { d.MoveSelected(1); }},
      {"set Kp",
       [&] {
         d.SetField({d.selection(), "joint", "Kp"}, "12.5");
       }},
      {"set mass",
       [&] {
         d.SetField({d.selection(), "frames[1]", "mass"}, "0.07");
       }},
      {"remove", [&] { d.RemoveSelected(); }},
      {"ball", [&] { d.AddObject(ObjectKind::kBall); }},
      {"box", [&] { d.AddObject(ObjectKind::kBox); }},
      {"cylinder", [&] { d.AddObject(ObjectKind::kCylinder); }},
      {"capsule", [&] { d.AddObject(ObjectKind::kCapsule); }},
      {"ramp", [&] { d.AddObject(ObjectKind::kRamp); }},
      {"object size",
       [&] {
         d.SetField({d.selection(), "", "size"}, "0.6 0.3 0.03");
       }},
      {"water", [&] { d.AddFluid(FluidKind::kWater); }},
      {"air", [&] { d.AddFluid(FluidKind::kAir); }},
      {"contact", [&] { d.AddContact(); }},
      {"friction",
       [&] {
         d.SetField({d.selection(), "", "friction"}, "0.9");
       }},
      {"terrain",
       [&] { d.SetTerrain(SourcePath("scenarios/terrain.png"), 0.3, 0.05); }},
      {"template", [&] {
         TemplateOptions t;
         t.chain.modules = 3;
         d.ApplyTemplate(t);
       }}};
  for (const auto& [name, edit] : edits) {
    const std::string before = Bytes(d);
    edit();
    const std::string after = Bytes(d);
    EXPECT_TRUE(before != after) << name << " changed nothing";
    ASSERT_TRUE(d.can_undo()) << name;
    d.Undo();
    EXPECT_TRUE(Bytes(d) == before) << "undo of " << name;
    d.Redo();
    EXPECT_TRUE(Bytes(d) == after) << "redo of " << name;
    EXPECT_NO_THROW(ReadScenarioString(after, name, d.scenario().base_dir))
        << name;
  }
}

TEST(StudioDesign, InvalidFieldValuesAreRefusedWithTheSchemaMessage) {
  Design d;
  d.AddPart(NextPart::kPitchModule);
  const std::string before = Bytes(d);
  const Selection m0{SelectionKind::kModule, 0, 0};
  try {
    d.SetField({m0, "frames[0]", "mass"}, "-1");
    FAIL() << "negative mass accepted";
  } catch (const DesignError& e) {
    EXPECT_NE(std::string(e.what()).find("positive"), std::string::npos)
        << e.what();
  }
  try {
    d.SetField({m0, "joint", "Kp"}, "fast");
    FAIL() << "text accepted as Kp";
  } catch (const DesignError& e) {
    EXPECT_NE(std::string(e.what()).find("fast"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(d.SetField({m0, "joint", "no_such_field"}, "1"), DesignError);
  EXPECT_EQ(Bytes(d), before);
  d.Undo();  // only the AddPart is on the stack
  EXPECT_FALSE(d.can_undo());
  EXPECT_TRUE(d.scenario().robots.empty());
}

TEST(StudioDesign, RefusesTwoSensorModulesSideBySide) {
  Design d;
  d.AddPart(NextPart::kPitchModule);
  d.AddPart(NextPart::kSensorModule);
  const std::string before = Bytes(d);
  EXPECT_THROW(d.AddPart(NextPart::kSensorModule), DesignError);
  EXPECT_EQ(Bytes(d), before);

  // Removing the module between two sensor modules names them as the
  // chain list does.
  Design e = Design::Open(testing::SourcePath("scenarios/case_study.xml"));
  e.Select({SelectionKind::kModule, 0, 0});
  try {
    e.RemoveSelected();
    FAIL() << "removed module 0";
  } catch (const DesignError& error) {
    EXPECT_NE(std::string(error.what())
                  .find("sensor modules S0 and S1 would be next to each other"),
              std::string::npos)
        << error.what();
  }
}

TEST(StudioDesign, PartByPartEqualsScenarioNew) {
  const std::string dir = TempDir("studio_design_new");
  // The case study's robot: a sensor module in front of, between and
  // behind 5 pitch-yaw modules, force plates, a front distance sensor.
  Design d;
  const NextPart order[] = {NextPart::kPitchModule, NextPart::kYawModule,
                            NextPart::kPitchModule, NextPart::kYawModule,
                            NextPart::kPitchModule};
  for (NextPart p : order) {
    d.AddPart(p);
    d.AddPart(NextPart::kSensorModule);
  }
  d.AddPart(NextPart::kSensorModule, Where::kFront);
  d.AddContact();
  d.SaveAs(dir + "/studio.xml");
  const std::string tool = ScenarioNew(
      {"--modules", "5", "--pattern", "pitch-yaw", "--sensors", "all",
       "--force-sensors", "--front-distance-sensor", "--friction", "0.5"},
      dir);
  EXPECT_TRUE(ReadFile(dir + "/studio.xml") == ReadFile(tool))
      << "diff " << dir << "/studio.xml " << tool;

  // The same edits on both give the same file again.
  Design from_tool = Design::Open(tool);
  for (Design* x : {&d, &from_tool}) {
    x->SetField({{SelectionKind::kModule, 0, 2}, "joint", "Kp"}, "14");
    x->Select({SelectionKind::kModule, 0, 4});
    x->AddObject(ObjectKind::kBall);
  }
  d.Save();
  from_tool.SaveAs(dir + "/edited.xml");
  EXPECT_TRUE(ReadFile(dir + "/studio.xml") == ReadFile(dir + "/edited.xml"))
      << "diff " << dir << "/studio.xml " << dir << "/edited.xml";
}

TEST(StudioDesign, AppendingPitchModulesEqualsScenarioNewPitch) {
  const std::string dir = TempDir("studio_design_pitch");
  Design d;
  for (int i = 0; i < 4; ++i) d.AddPart(NextPart::kPitchModule);
  d.SaveAs(dir + "/studio.xml");
  EXPECT_TRUE(ReadFile(dir + "/studio.xml") ==
              ReadFile(ScenarioNew({"--modules", "4"}, dir)))
      << "diff " << dir << "/studio.xml " << dir << "/new.xml";
}

TEST(StudioDesign, MoveAndRemoveKeepTheChainWhole) {
  Design d;
  d.AddPart(NextPart::kPitchModule);
  d.AddPart(NextPart::kYawModule);
  d.AddPart(NextPart::kSensorModule);
  d.AddPart(NextPart::kPitchModule);
  d.Select({SelectionKind::kSensorModule, 0, 0});
  d.MoveSelected(-1);  // between module 0 and 1 now
  const Robot& r = d.scenario().robots[0];
  ASSERT_EQ(r.sensor_modules.size(), 1u);
  EXPECT_EQ(r.sensor_modules[0].left_mod_nr, 0);
  EXPECT_EQ(r.sensor_modules[0].right_mod_nr, 1);
  EXPECT_EQ(d.selection(), (Selection{SelectionKind::kSensorModule, 0, 0}));
  d.Select({SelectionKind::kModule, 0, 1});
  d.RemoveSelected();
  const Robot& r2 = d.scenario().robots[0];
  ASSERT_EQ(r2.modules.size(), 2u);
  EXPECT_EQ(r2.modules[1].mod_nr, 1);
  EXPECT_EQ(r2.modules[1].axis, Axis::kPitch);
  EXPECT_EQ(r2.sensor_modules[0].right_mod_nr, 1);
}

// Every part touches the one in front of it along x: a module's front
// frame the previous part's back face, its back frame its own front frame.
void ExpectChainTouches(const Robot& r) {
  double back = NAN;  // back face of the part in front
  auto touches = [&](double front_face, double length,
                     const std::string& what) {
    if (!std::isnan(back)) {
      EXPECT_NEAR(front_face, back, 1e-12) << what;
    }
    back = front_face - length;
  };
  for (const ChainSlot& slot : ChainOrder(r)) {
    if (slot.sensor) {
      const SensorModule& sm = r.sensor_modules[slot.source];
      touches(sm.position.x() + sm.size.x() / 2, sm.size.x(), sm.guid);
    } else {
      const Module& m = r.modules[slot.source];
      for (const Frame& f : m.frames) {
        touches(f.position.x() + f.scale.x() / 2, f.scale.x(), f.guid);
      }
      EXPECT_NEAR(m.position.x(),
                  m.frames[1].position.x() + m.frames[1].scale.x() / 2, 1e-12);
    }
  }
}

TEST(StudioDesign, ScalingAFrameSlidesThePartsBehindItToStayAttached) {
  Design d;
  for (NextPart p : {NextPart::kPitchModule, NextPart::kYawModule,
                     NextPart::kSensorModule, NextPart::kPitchModule}) {
    d.AddPart(p, Where::kTail);
  }
  d.AddPart(NextPart::kSensorModule, Where::kFront);
  const double hinge0 = d.scenario().robots[0].modules[0].position.x();
  const double tail = d.scenario().robots[0].modules[2].position.x();
  d.SetField({{SelectionKind::kModule, 0, 1}, "frames[0]", "scale"},
             "0.09 0.05 0.05");
  const Robot& r = d.scenario().robots[0];
  ExpectChainTouches(r);
  EXPECT_EQ(r.modules[0].position.x(), hinge0);  // in front: unmoved
  EXPECT_NEAR(r.modules[2].position.x(), tail - 0.04, 1e-12);
  // What sits on the sensor module behind moved with it.
  const SensorModule& sm = r.sensor_modules[1];
  ASSERT_TRUE(sm.force_sensor);
  EXPECT_NEAR(sm.force_sensor->position.x(), sm.position.x(), 1e-12);
  // A sensor module that grows, and a later structural edit, keep it too.
  d.SetField({{SelectionKind::kSensorModule, 0, 1}, "", "size"},
             "0.08 0.05 0.05");
  ExpectChainTouches(d.scenario().robots[0]);
  d.Select({SelectionKind::kModule, 0, 1});
  d.AddPart(NextPart::kPitchModule);
  ExpectChainTouches(d.scenario().robots[0]);
  EXPECT_EQ(d.scenario().robots[0].modules[1].frames[0].scale.x(), 0.09);
  EXPECT_EQ(d.scenario().robots[0].sensor_modules[1].size.x(), 0.08);
  d.Undo();
  d.Undo();
  d.Undo();
  EXPECT_NEAR(d.scenario().robots[0].modules[2].position.x(), tail, 1e-12);
}

// Pitch, sensor, yaw, sensor, pitch: every sensor module with a plate.
Design TwoSensorModules() {
  Design d;
  for (NextPart p :
       {NextPart::kPitchModule, NextPart::kSensorModule, NextPart::kYawModule,
        NextPart::kSensorModule, NextPart::kPitchModule}) {
    d.AddPart(p, Where::kTail);
  }
  return d;
}

TEST(StudioDesign, ForcePlatesAreChosenPerSensorModule) {
  Design d = TwoSensorModules();
  ASSERT_TRUE(d.scenario().robots[0].sensor_modules[0].force_sensor);
  ASSERT_TRUE(d.scenario().robots[0].sensor_modules[1].force_sensor);
  const double z = d.scenario().robots[0].modules[0].position.z();
  d.Select({SelectionKind::kSensorModule, 0, 0});
  d.SetForcePlate(false);
  const Robot& r = d.scenario().robots[0];
  EXPECT_FALSE(r.sensor_modules[0].force_sensor);
  EXPECT_FALSE(r.sensor_modules[0].force_sensor_lock);
  ASSERT_TRUE(r.sensor_modules[1].force_sensor);
  EXPECT_EQ(r.modules[0].position.z(), z);  // still on the other plate
  // The choice survives structural edits, and the plate changes face.
  d.Select({SelectionKind::kModule, 0, 0});
  d.AddPart(NextPart::kYawModule, Where::kFront);
  EXPECT_FALSE(d.scenario().robots[0].sensor_modules[0].force_sensor);
  EXPECT_TRUE(d.scenario().robots[0].sensor_modules[1].force_sensor);
  d.SetField(
      {{SelectionKind::kSensorModule, 0, 1}, "force_sensor", "sensorPosition"},
      "2");
  const SensorModule& sm = d.scenario().robots[0].sensor_modules[1];
  EXPECT_NEAR(sm.force_sensor->position.z(),
              sm.position.z() + sm.size.z() / 2 + sm.force_sensor->size.z() / 2,
              1e-12);  // on top now
  // Without any plate the chain comes down to the ground, and back up.
  d.Select({SelectionKind::kSensorModule, 0, 1});
  d.SetForcePlate(false);
  const double ground_z = d.scenario().robots[0].modules[0].position.z();
  EXPECT_NEAR(ground_z, z - ForceSensor().size.z(), 1e-12);
  d.SetForcePlate(true);
  EXPECT_NEAR(d.scenario().robots[0].modules[0].position.z(), z, 1e-12);
  EXPECT_TRUE(d.scenario().robots[0].sensor_modules[1].force_sensor_lock);
  EXPECT_THROW(
      {
        d.Select({SelectionKind::kModule, 0, 0});
        d.SetForcePlate(true);
      },
      DesignError);
  // Saved and read back, as the simulator would.
  const Scenario back = ReadScenarioString(Bytes(d), "plates", "");
  EXPECT_FALSE(back.robots[0].sensor_modules[0].force_sensor);
  EXPECT_TRUE(back.robots[0].sensor_modules[1].force_sensor);
}

TEST(StudioDesign, DistanceSensorsGoOnEveryFaceThatLooksOut) {
  Design d = TwoSensorModules();
  d.Select({SelectionKind::kSensorModule, 0, 1});
  // What the face picker offers first: the faces that will be taken.
  EXPECT_EQ(d.OpenRayFaces(), (std::vector<int>{0, 1, 2, 3}));
  for (int face : {0, 1, 2, 3}) d.AddDistanceSensor(face);
  EXPECT_TRUE(d.OpenRayFaces().empty());
  // Between two modules, front and back touch them: a ray there starts
  // inside a module and would read 0.
  for (int face : {4, 5}) {
    try {
      d.AddDistanceSensor(face);
      ADD_FAILURE() << "a ray on face " << face << " was added";
    } catch (const DesignError& e) {
      EXPECT_THAT(e.what(), HasSubstr("runs into 'snake/m"));
    }
  }
  const SensorModule& sm = d.scenario().robots[0].sensor_modules[1];
  ASSERT_EQ(sm.distance_sensors.size(), 4u);
  ASSERT_EQ(sm.distance_sensor_locks.size(), 4u);
  for (const DistanceSensor& ray : sm.distance_sensors) {
    const Eigen::Vector3d n = SensorFaceNormal(ray.sensor_position);
    EXPECT_TRUE(ray.ray_direction.isApprox(n)) << ray.guid;
    // Just outside its face, looking out of it.
    const double out = (ray.position - sm.position).dot(n);
    EXPECT_NEAR(out,
                std::abs(n.dot(sm.size)) / 2 + std::abs(n.dot(ray.size)) / 2,
                1e-12)
        << ray.guid;
  }
  EXPECT_THROW(d.AddDistanceSensor(3), DesignError);  // face taken
  d.RemoveDistanceSensor(1);                          // the one on face 1
  // A ray moved to another face sits on it and looks out of it.
  d.SetField({{SelectionKind::kSensorModule, 0, 1},
              "distance_sensors[0]",
              "sensorPosition"},
             "1");
  const SensorModule& moved = d.scenario().robots[0].sensor_modules[1];
  EXPECT_TRUE(moved.distance_sensors[0].ray_direction.isApprox(
      Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(moved.distance_sensors[0].position.y() - moved.position.y(),
              moved.size.y() / 2 + moved.distance_sensors[0].size.y() / 2,
              1e-12);
  d.AddDistanceSensor(0);
  for (const char* face : {"9", "4"}) {
    EXPECT_THROW(d.SetField({{SelectionKind::kSensorModule, 0, 1},
                             "distance_sensors[0]",
                             "sensorPosition"},
                            face),
                 DesignError)
        << face;
  }
  // The simulator builds it from the file: four rays on one module.
  const Physics physics(ReadScenarioString(Bytes(d), "rays", ""));
  EXPECT_EQ(physics.ReadRobotState(0).sensor_modules.at(1).distances.size(),
            4u);
}

// The camera (sensor_kind.h's "camera", a kind of many like the distance
// sensor) is added per face of the selected sensor module, refused where
// it would see only its own robot, shown by the inspector with its fields,
// and removed; the simulator builds the MuJoCo camera from the saved file.
TEST(StudioDesign, CamerasAreAddedPerFaceEditedAndRemoved) {
  Design d = TwoSensorModules();
  d.Select({SelectionKind::kSensorModule, 0, 1});
  // Between two modules the front and back faces look into them.
  EXPECT_EQ(d.OpenCameraFaces(), (std::vector<int>{0, 1, 2, 3}));
  for (int face : {4, 5}) {
    try {
      d.AddCamera(face);
      ADD_FAILURE() << "a camera on face " << face << " was added";
    } catch (const DesignError& e) {
      EXPECT_THAT(e.what(), HasSubstr("would see only that part"));
    }
  }
  d.AddCamera(1);
  d.AddCamera(3);
  EXPECT_THROW(d.AddCamera(1), DesignError);  // face taken
  EXPECT_EQ(d.OpenCameraFaces(), (std::vector<int>{0, 2}));
  const SensorModule& sm = d.scenario().robots[0].sensor_modules[1];
  ASSERT_EQ(sm.cameras.size(), 2u);
  EXPECT_EQ(sm.cameras[0].sensor_position, 1);
  EXPECT_EQ(sm.cameras[1].sensor_position, 3);
  EXPECT_NE(sm.cameras[0].guid, sm.cameras[1].guid);
  EXPECT_EQ(sm.cameras[0].width, Camera().width);  // the default picture

  // The inspector: one group per camera, titled by the kind's label.
  const Selection sel{SelectionKind::kSensorModule, 0, 1};
  Scenario copy = d.scenario();
  std::vector<std::string> titles;
  std::set<std::string> fields;
  for (const FieldGroup& g : InspectorFields(copy, sel)) {
    if (g.sub.rfind("cameras[", 0) != 0) continue;
    titles.push_back(g.title);
    for (const FieldRef& f : g.fields) fields.insert(f.info().xml);
  }
  EXPECT_EQ(titles, (std::vector<std::string>{"Camera 0", "Camera 1"}));
  for (const char* xml : {"sensorPosition", "fovy", "width", "height", "rate",
                          "near", "far", "tilt", "noise", "seed"}) {
    EXPECT_TRUE(fields.count(xml)) << xml;
  }
  d.SetField({sel, "cameras[1]", "width"}, "320");
  EXPECT_EQ(d.FieldText({sel, "cameras[1]", "width"}), "320");
  EXPECT_THROW(d.SetField({sel, "cameras[1]", "width"}, "100000"), DesignError);
  // Turned to look into the neighbour module: refused like a ray.
  EXPECT_THROW(d.SetField({sel, "cameras[0]", "sensorPosition"}, "4"),
               DesignError);

  // The simulator builds it from the file: two MuJoCo cameras.
  {
    const Physics physics(ReadScenarioString(Bytes(d), "cameras", ""));
    EXPECT_EQ(physics.model()->ncam, 2);
  }
  d.RemoveCamera(0);
  ASSERT_EQ(d.scenario().robots[0].sensor_modules[1].cameras.size(), 1u);
  EXPECT_EQ(d.scenario().robots[0].sensor_modules[1].cameras[0].width, 320);
  EXPECT_THROW(d.RemoveCamera(5), DesignError);
  d.Undo();
  EXPECT_EQ(d.scenario().robots[0].sensor_modules[1].cameras.size(), 2u);
  const Scenario back = ReadScenarioString(Bytes(d), "cameras", "");
  EXPECT_EQ(back.robots[0].sensor_modules[1].cameras,
            d.scenario().robots[0].sensor_modules[1].cameras);
}

// A scene object carries cameras as a sensor module does: added per face
// of the box around it (a static one is a fixed camera on the world),
// edited in the inspector's "Camera k" group, saved and built as
// scene/obj<k>/camera, removed.
TEST(StudioDesign, ASceneObjectGetsCamerasPerFace) {
  Design d = TwoSensorModules();
  d.AddObject(ObjectKind::kBox);
  const Selection sel = d.selection();
  ASSERT_EQ(sel.kind, SelectionKind::kSceneObject);
  EXPECT_EQ(d.OpenCameraFaces(), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  d.SetField({sel, "", "isStatic"}, "true");
  d.AddCamera(5);
  d.AddCamera(1);
  EXPECT_THROW(d.AddCamera(5), DesignError);  // face taken
  EXPECT_EQ(d.OpenCameraFaces(), (std::vector<int>{0, 2, 3, 4}));
  const SceneObject& o = d.scenario().scene_objects.at(sel.index);
  ASSERT_EQ(o.cameras.size(), 2u);
  EXPECT_EQ(o.cameras[0].sensor_position, 5);
  EXPECT_EQ(o.cameras[0].guid, o.guid + "/c0");

  Scenario copy = d.scenario();
  std::vector<std::string> titles;
  for (const FieldGroup& g : InspectorFields(copy, sel)) {
    titles.push_back(g.title);
  }
  EXPECT_EQ(titles,
            (std::vector<std::string>{"Scene object", "Camera 0", "Camera 1"}));
  d.SetField({sel, "cameras[0]", "tilt"}, "15");
  EXPECT_EQ(d.FieldText({sel, "cameras[0]", "tilt"}), "15");
  EXPECT_THROW(d.SetField({sel, "cameras[0]", "height"}, "4000"), DesignError);

  const Scenario back = ReadScenarioString(Bytes(d), "object_cameras", "");
  EXPECT_EQ(back.scene_objects.at(sel.index).cameras,
            d.scenario().scene_objects.at(sel.index).cameras);
  {
    const Physics physics(back);
    EXPECT_GE(
        mj_name2id(
            physics.model(), mjOBJ_CAMERA,
            ("scene/obj" + std::to_string(sel.index) + "/camera").c_str()),
        0);
  }
  d.RemoveCamera(0);
  ASSERT_EQ(d.scenario().scene_objects.at(sel.index).cameras.size(), 1u);
  EXPECT_EQ(d.scenario().scene_objects.at(sel.index).cameras[0].sensor_position,
            1);
  // Nothing selected that carries cameras: refused, no faces offered.
  d.Select({SelectionKind::kModule, 0, 0});
  EXPECT_TRUE(d.OpenCameraFaces().empty());
  EXPECT_THROW(d.AddCamera(4), DesignError);
}

TEST(StudioDesign, ASensorModuleAtTheTailLooksOutOfItsBack) {
  Design d;
  d.AddPart(NextPart::kPitchModule, Where::kTail);
  d.AddPart(NextPart::kSensorModule, Where::kTail);
  d.Select({SelectionKind::kSensorModule, 0, 0});
  d.AddDistanceSensor(5);
  EXPECT_THROW(d.AddDistanceSensor(4), DesignError);  // module 0 is there
  EXPECT_EQ(d.scenario().robots[0].sensor_modules[0].distance_sensors.size(),
            1u);
}

TEST(StudioInspector, ShowsComputedNumbersShortAndLeavesTheRestAlone) {
  EXPECT_EQ(ShortNumbers("0.027000000000000003"), "0.027");
  EXPECT_EQ(ShortNumbers("-0.24500000000000005 0 0.025"), "-0.245 0 0.025");
  EXPECT_EQ(ShortNumbers("1e-05"), "1e-05");
  EXPECT_EQ(ShortNumbers("0.1234567890123"), "0.123456789");
  EXPECT_EQ(ShortNumbers("12"), "12");
}

// Labels are words with units; the name in the file is in the tooltip, so
// a student reading the XML finds the field.
TEST(StudioInspector, EveryFieldHasAHumanLabelAndItsXmlNameInTheTooltip) {
  int fields = 0;
  for (const PartKind kind : AllPartKinds()) {
    for (const FieldSpec& spec : FieldSpecsOf(kind)) {
      const FieldInfo& info = spec.info;
      ASSERT_NE(info.label, nullptr) << info.xml;
      EXPECT_NE(FieldLabel(info), info.xml);
      EXPECT_THAT(FieldTooltip(info),
                  HasSubstr(std::string("<") + info.xml + ">"));
      ++fields;
    }
  }
  EXPECT_GT(fields, 80);
  // As the issue asked for them.
  Design d = TwoSensorModules();
  const auto label_of = [&](const Selection& sel, const std::string& sub,
                            const std::string& xml) {
    Scenario s = d.scenario();
    for (const FieldGroup& g : InspectorFields(s, sel)) {
      for (const FieldRef& f : g.fields) {
        if (g.sub == sub && f.info().xml == xml) return FieldLabel(f.info());
      }
    }
    return std::string("(no field)");
  };
  EXPECT_EQ(label_of({SelectionKind::kModule, 0, 0}, "joint", "Kp"),
            "gain Kp (1/s)");
  EXPECT_EQ(label_of({SelectionKind::kSensorModule, 0, 0}, "", "leftMod_Nr"),
            "left neighbour module");
  d.Select({SelectionKind::kSensorModule, 0, 0});
  d.AddDistanceSensor(d.OpenRayFaces().front());
  EXPECT_EQ(label_of({SelectionKind::kSensorModule, 0, 0},
                     "distance_sensors[0]", "max_rayDistance"),
            "max ray distance (m)");
}

TEST(StudioDesign, OpensEveryScenarioInTheScenariosFolder) {
  for (const auto& entry :
       std::filesystem::directory_iterator(SourcePath("scenarios"))) {
    const std::string path = entry.path().string();
    if (entry.path().extension() != ".xml" ||
        path.find("genome") != std::string::npos) {
      continue;
    }
    Design d = Design::Open(path);
    EXPECT_FALSE(d.scenario().robots.empty()) << path;
    if (IsOriginalMrsimFile(path)) {
      // Converted on open; saving writes a native file beside it.
      EXPECT_TRUE(d.dirty()) << path;
      EXPECT_NE(d.path().find(".native.xml"), std::string::npos) << d.path();
      EXPECT_NE(d.note().find("original MRSim"), std::string::npos) << d.note();
      // Metres: the original's 10 cm frames are 0.1 m, not 10 m.
      EXPECT_LT(d.scenario().robots[0].modules[0].frames[0].scale.x(), 1.0);
    } else {
      EXPECT_FALSE(d.dirty()) << path;
      EXPECT_TRUE(d.note().empty()) << path;
    }
  }
}

TEST(StudioDesign, DirtyUntilSavedAndAfterUndoingBackToSaved) {
  const std::string dir = TempDir("studio_design_dirty");
  Design d = Design::Open(dir + "/fresh.xml");
  EXPECT_FALSE(d.dirty());
  d.AddPart(NextPart::kPitchModule);
  EXPECT_TRUE(d.dirty());
  d.Save();
  EXPECT_FALSE(d.dirty());
  EXPECT_TRUE(std::filesystem::exists(dir + "/fresh.xml"));
  d.AddObject(ObjectKind::kBox);
  EXPECT_TRUE(d.dirty());
  d.Undo();
  EXPECT_FALSE(d.dirty());
}

TEST(StudioInspector, FieldsThatDoNothingAreNotOffered) {
  ChainScenarioOptions options;
  options.chain.modules = 2;
  options.chain.sensor_after = {-1};
  options.chain.force_sensors = true;
  options.chain.front_distance_sensor = true;
  Scenario s = MakeChainScenario(options);
  SceneObject ball;
  ball.guid = "ball";
  ball.position = Eigen::Vector3d(1, 0, 0.1);
  s.scene_objects.push_back(ball);
  const std::map<std::string, std::vector<std::string>> inert = {
      // Lock is refused on a module, and its servo is always on.
      {"joint", {"type", "breakForce", "servo"}},
      {"frames[0]", {"rotation"}},
      {"frames[1]", {"rotation"}},
      {"", {"rotation", "forceLockPosition", "distanceLockPosition"}},
      {"force_sensor", {"position", "rotation"}},
      {"distance_sensors[0]", {"rotation", "ray_Resolution"}}};
  int groups = 0;
  for (const Selection& sel : {Selection{SelectionKind::kModule, 0, 0},
                               Selection{SelectionKind::kSensorModule, 0, 0},
                               Selection{SelectionKind::kSceneObject, 0, 0}}) {
    for (const FieldGroup& g : InspectorFields(s, sel)) {
      ++groups;
      auto it = inert.find(g.sub);
      if (it == inert.end()) continue;
      for (const FieldRef& f : g.fields) {
        for (const std::string& name : it->second) {
          EXPECT_NE(name, f.info().xml) << g.title << " offers " << name;
        }
      }
    }
  }
  EXPECT_GE(groups, 7);
  // The quaternion that does place the part is still offered.
  bool quat = false;
  for (const FieldGroup& g :
       InspectorFields(s, Selection{SelectionKind::kModule, 0, 0})) {
    for (const FieldRef& f : g.fields) {
      quat |= std::string(f.info().xml) == "quatRotation";
    }
  }
  EXPECT_TRUE(quat);
}

// A static object is welded to the world: its mass moves nothing, so the
// inspector offers it only for a movable one (REQ-1.4.5).
TEST(StudioInspector, AStaticObjectsMassIsNotOffered) {
  Scenario s = MakeChainScenario(ChainScenarioOptions{});
  SceneObject& rock = s.scene_objects.emplace_back();
  rock.guid = "rock";
  const Selection object{SelectionKind::kSceneObject, 0, 0};
  auto offers_mass = [&]() {
    for (const FieldGroup& g : InspectorFields(s, object)) {
      for (const FieldRef& f : g.fields) {
        if (std::string(f.info().xml) == "mass") return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(offers_mass());
  rock.is_static = true;
  EXPECT_FALSE(offers_mass());
}

TEST(StudioInspector, DirectionalFrictionsAreOfferedOnlyWhenDirectionalIsOn) {
  Scenario s = MakeChainScenario(ChainScenarioOptions{});
  s.contact_frictions.emplace_back();
  const Selection contact{SelectionKind::kContactFriction, 0, 0};
  auto offered = [&]() {
    std::set<std::string> names;
    for (const FieldGroup& g : InspectorFields(s, contact)) {
      for (const FieldRef& f : g.fields) names.insert(f.info().xml);
    }
    return names;
  };
  const std::vector<std::string> by_direction = {
      "forwardFriction", "backwardFriction", "lateralFriction",
      "torsionalFriction", "rollingFriction"};
  std::set<std::string> off = offered();
  EXPECT_EQ(off.count("directional"), 1u);
  EXPECT_EQ(off.count("friction"), 1u);
  for (const std::string& name : by_direction) {
    EXPECT_EQ(off.count(name), 0u) << name << " offered with directional off";
  }
  // Ticking it swaps the single coefficient for the per-direction ones.
  for (const FieldGroup& g : InspectorFields(s, contact)) {
    for (const FieldRef& f : g.fields) {
      if (std::string(f.info().xml) == "directional") f.SetText("true");
    }
  }
  std::set<std::string> on = offered();
  EXPECT_EQ(on.count("friction"), 0u);
  for (const std::string& name : by_direction) {
    EXPECT_EQ(on.count(name), 1u) << name << " hidden with directional on";
  }
}

TEST(StudioInspector, AnEmbeddedMeshShowsItsFileNameNotItsBytes) {
  const std::string dir = TempDir("studio_embedded_mesh_name");
  const std::string stl = dir + "/link.stl";
  {
    std::ofstream out(stl, std::ios::binary);
    out << std::string(3000, 'x');  // the bytes only need to be carried
  }
  const std::string shape = EmbedMeshFile(stl);
  ASSERT_TRUE(IsEmbeddedMesh(shape));
  EXPECT_EQ(ShapeSummary(shape), "link.stl (embedded, 3.0 kB)");
  EXPECT_EQ(ShapeSummary("Box"), "Box");
  EXPECT_EQ(ShapeSummary("meshes/arm.stl"), "meshes/arm.stl");
  EXPECT_EQ(ShapeSummary("base64:"), "mesh (embedded, malformed)");
}

TEST(StudioInspector, FilesWithFieldsThatDoNothingStillLoadAndKeepThem) {
  ChainScenarioOptions options;
  options.chain.modules = 2;
  options.chain.sensor_after = {-1};
  options.chain.force_sensors = true;
  options.chain.front_distance_sensor = true;
  Scenario s = MakeChainScenario(options);
  Robot& r = s.robots[0];
  r.modules[0].frames[0].rotation = Eigen::Vector3d(10, 20, 30);
  r.modules[0].joint.break_force = 50;
  SensorModule& sm = r.sensor_modules[0];
  sm.force_lock_position = Eigen::Vector3d(1, 2, 3);
  sm.distance_lock_position = Eigen::Vector3d(4, 5, 6);
  sm.force_sensor->position = Eigen::Vector3d(7, 8, 9);
  sm.distance_sensors[0].ray_resolution = 0.25;
  const std::string dir = TempDir("studio_inert_fields");
  const std::string file = dir + "/inert.xml";
  WriteScenarioFile(s, file);
  const Design d = Design::Open(file);
  const Scenario& back = d.scenario();
  EXPECT_EQ(back.robots[0].modules[0].frames[0].rotation,
            Eigen::Vector3d(10, 20, 30));
  EXPECT_EQ(back.robots[0].modules[0].joint.break_force, 50);
  EXPECT_EQ(back.robots[0].sensor_modules[0].distance_sensors[0].ray_resolution,
            0.25);
  EXPECT_EQ(back.robots[0].sensor_modules[0].force_sensor->position,
            Eigen::Vector3d(7, 8, 9));
}

TEST(StudioMesh, AMeshForEveryPitchModuleRestacksAndNewModulesReuseIt) {
  const std::string dir = TempDir("studio_mesh_kind");
  {
    // An 80 x 50 x 40 mm block, its own origin at its centre.
    std::ofstream out(dir + "/link.stl", std::ios::binary);
    out << BinaryStl(BoxMesh(Eigen::Vector3d(0.08, 0.05, 0.04)), 1.0, "link");
  }
  ChainScenarioOptions options;
  options.chain.modules = 3;
  options.chain.pattern = ChainPattern::kPitchYaw;
  WriteScenarioFile(MakeChainScenario(options), dir + "/robot.xml");
  Design d = Design::Open(dir + "/robot.xml");
  d.Select({SelectionKind::kModule, 0, 0});
  d.SetModuleMesh(dir + "/link.stl", true);
  const Robot& r = d.scenario().robots[0];
  for (const Module& m : r.modules) {
    for (const Frame& f : m.frames) {
      EXPECT_EQ(f.shape, m.axis == Axis::kPitch ? "link.stl" : "Box");
    }
  }
  // Pitch modules are 160 mm long now, the yaw module 100 mm: hinges
  // 0.16 / 2 + 0.1 / 2 apart.
  EXPECT_NEAR(r.modules[0].position.x() - r.modules[1].position.x(),
              0.08 + 0.05, 1e-6);  // STL stores float32
  EXPECT_NEAR(r.modules[1].position.x() - r.modules[2].position.x(),
              0.05 + 0.08, 1e-6);  // STL stores float32
  EXPECT_NEAR(r.modules[0].frames[0].position.x() - r.modules[0].position.x(),
              0.04, 1e-6);  // STL stores float32
  // One undo step.
  d.Undo();
  EXPECT_EQ(d.scenario().robots[0].modules[0].frames[0].shape, "Box");
  d.Redo();
  d.Select({SelectionKind::kModule, 0, 2});
  d.AddPart(NextPart::kPitchModule);
  const Robot& grown = d.scenario().robots[0];
  ASSERT_EQ(grown.modules.size(), 4u);
  EXPECT_EQ(grown.modules[3].frames[0].shape, "link.stl");
  EXPECT_NEAR(grown.modules[2].position.x() - grown.modules[3].position.x(),
              0.08 + 0.08, 1e-6);  // STL stores float32
  // The physics builds it, and the saved file reads back.
  d.SaveAs(dir + "/robot_mesh.xml");
  const Scenario back = ReadScenarioFile(dir + "/robot_mesh.xml");
  EXPECT_EQ(back.robots[0].modules[3].frames[1].shape, "link.stl");
  Physics physics(back);
  EXPECT_GT(physics.model()->nmesh, 0);
}

// Most CAD programs export millimetres: an 80 mm link read as metres is
// 80 m long. The studio spots it and one edit scales it back.
TEST(StudioMesh, AMeshInMillimetresIsSpottedAndScaledByOneThousandth) {
  const std::string dir = TempDir("studio_mesh_mm");
  {
    std::ofstream out(dir + "/link_mm.stl", std::ios::binary);
    out << BinaryStl(BoxMesh(Eigen::Vector3d(80, 50, 40)), 1.0, "link");
  }
  ChainScenarioOptions options;
  options.chain.modules = 3;
  options.chain.pattern = ChainPattern::kPitchYaw;
  WriteScenarioFile(MakeChainScenario(options), dir + "/robot.xml");
  Design d = Design::Open(dir + "/robot.xml");
  EXPECT_TRUE(d.OversizedMeshes().empty()) << "boxes in metres";
  d.Select({SelectionKind::kModule, 0, 0});
  d.SetModuleMesh(dir + "/link_mm.stl", true);
  const std::vector<Design::OversizedMesh> big = d.OversizedMeshes();
  ASSERT_EQ(big.size(), 1u);  // the shape once, though two modules use it
  EXPECT_EQ(big[0].shape, "link_mm.stl");
  EXPECT_NEAR(big[0].longest, 80, 1e-4);

  const std::string before = Bytes(d);
  d.ScaleMesh("link_mm.stl", 0.001);
  EXPECT_TRUE(d.OversizedMeshes().empty());
  const Robot& r = d.scenario().robots[0];
  for (const Module& m : r.modules) {
    for (const Frame& f : m.frames) {
      if (f.is_mesh()) {
        EXPECT_NEAR(f.scale.x(), 0.001, 1e-12);
      }
    }
  }
  // Restacked: pitch modules 160 mm long, the yaw module 100 mm.
  EXPECT_NEAR(r.modules[0].position.x() - r.modules[1].position.x(),
              0.08 + 0.05, 1e-6);  // STL stores float32
  // One undo step.
  d.Undo();
  EXPECT_EQ(Bytes(d), before);
}

TEST(StudioMesh, AnUnreadableMeshIsRefusedAndChangesNothing) {
  const std::string dir = TempDir("studio_mesh_bad");
  {
    std::ofstream out(dir + "/bad.stl", std::ios::binary);
    out << "solid nothing here";
  }
  WriteScenarioFile(MakeChainScenario({}), dir + "/robot.xml");
  Design d = Design::Open(dir + "/robot.xml");
  d.Select({SelectionKind::kModule, 0, 0});
  const long revision = d.revision();
  EXPECT_THROW(d.SetModuleMesh(dir + "/bad.stl", false), DesignError);
  EXPECT_EQ(d.revision(), revision);
}

TEST(StudioDesign, SaveWithEmbeddingCarriesTheTerrainAndKeepsThePathOnScreen) {
  const std::string dir = TempDir("studio_design_embed");
  std::filesystem::copy_file(SourcePath("scenarios/terrain.png"),
                             dir + "/ground.png",
                             std::filesystem::copy_options::overwrite_existing);
  Scenario s = ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  s.scene.height_image = "ground.png";
  WriteScenarioFile(s, dir + "/design.xml");
  Design d = Design::Open(dir + "/design.xml");
  d.Save(/*embed_assets=*/true);
  EXPECT_FALSE(d.dirty());
  EXPECT_EQ(d.scenario().scene.height_image, "ground.png");
  std::filesystem::remove(dir + "/ground.png");
  const Scenario saved = ReadScenarioFile(dir + "/design.xml");
  EXPECT_EQ(saved.scene.height_image.rfind("base64:", 0), 0u);
  EXPECT_NO_THROW(Physics physics(saved));
}

}  // namespace
}  // namespace mrsim::studio

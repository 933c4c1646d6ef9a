#include "sim_core/mjcf/mjcf_builder.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "sim_core/mesh/base64.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mjcf/contact_model.h"
#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_ptr.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/terrain.h"
#include "tests/common/child_process.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

using testing::ChildProcess;
using testing::TempDir;

MjModelPtr Load(const std::string& path) {
  char error[1000] = {0};
  MjModelPtr m(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
  EXPECT_TRUE(m) << error;
  return m;
}

std::string WriteFile(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

Scenario SnakeScenario() {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 11;
  options.sensor_after = {-1, 5};
  options.force_sensors = true;
  options.front_distance_sensor = true;
  s.robots.push_back(MakeChain(options));
  return s;
}

TEST(MjcfBuilder, SnakeExportPassesMujocoTestxml) {
  const std::string dir = TempDir("mjcf_testxml");
  const std::string path =
      WriteFile(dir + "/snake.xml", BuildMjcf(SnakeScenario()));
  // mujoco-testxml compiles, saves and reloads the model and compares.
  ChildProcess p({"/bin/sh", "-c",
                  "cd '" + dir + "' && /usr/bin/mujoco-testxml snake.xml"},
                 dir + "/testxml.log");
  ASSERT_EQ(p.Wait(60), 0) << p.Output();
  EXPECT_EQ(p.Output().find("Error"), std::string::npos) << p.Output();
}

TEST(MjcfBuilder, NamesFollowTheChain) {
  const std::string dir = TempDir("mjcf_names");
  MjModelPtr m =
      Load(WriteFile(dir + "/snake.xml", BuildMjcf(SnakeScenario())));
  ASSERT_TRUE(m);
  for (int i = 0; i < 11; ++i) {
    EXPECT_GE(mj_name2id(m.get(), mjOBJ_BODY,
                         mjcf_names::FrameBody("snake", i, 0).c_str()),
              0);
    EXPECT_GE(mj_name2id(m.get(), mjOBJ_BODY,
                         mjcf_names::FrameBody("snake", i, 1).c_str()),
              0);
    const int joint =
        mj_name2id(m.get(), mjOBJ_JOINT,
                   ("snake/m" + std::to_string(i) + "/hinge").c_str());
    ASSERT_GE(joint, 0);
    EXPECT_EQ(m->jnt_type[joint], mjJNT_HINGE);
    EXPECT_TRUE(m->jnt_limited[joint]);
    const int servo =
        mj_name2id(m.get(), mjOBJ_ACTUATOR,
                   ("snake/m" + std::to_string(i) + "/servo").c_str());
    ASSERT_GE(servo, 0);
    EXPECT_EQ(m->actuator_trnid[2 * servo], joint);
  }
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_SENSOR, "snake/sm0/force"), 0);
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_SENSOR, "snake/sm1/force"), 0);
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_SITE, "snake/sm0/distance"), 0);
  EXPECT_GE(mj_name2id(m.get(), mjOBJ_GEOM, "scene/terrain"), 0);
  // One free root, hinges for the rest; locks add no joints.
  EXPECT_EQ(m->njnt, 12);
  EXPECT_EQ(m->nq, 7 + 11);
  EXPECT_EQ(m->neq, 0);
}

TEST(MjcfBuilder, PitchAxisIsAcrossTheChainAndYawVertical) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 2;
  options.pattern = ChainPattern::kPitchYaw;
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  const mjModel* m = physics.model();
  const mjData* d = physics.data();
  const int pitch = mj_name2id(m, mjOBJ_JOINT, "snake/m0/hinge");
  const int yaw = mj_name2id(m, mjOBJ_JOINT, "snake/m1/hinge");
  EXPECT_NEAR(std::abs(d->xaxis[3 * pitch + 1]), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(d->xaxis[3 * yaw + 2]), 1.0, 1e-9);
  // The anchor is the module position.
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(d->xanchor[3 * pitch + i], s.robots[0].modules[0].position[i],
                1e-12);
  }
}

TEST(MjcfBuilder, MaterialPairsBecomeContactParameters) {
  Scenario s = SnakeScenario();
  const std::string dir = TempDir("mjcf_contacts");
  MjModelPtr m = Load(WriteFile(dir + "/snake.xml", BuildMjcf(s)));
  ASSERT_TRUE(m);
  // plastic/plastic is on the geoms themselves.
  const int g = mj_name2id(m.get(), mjOBJ_GEOM, "snake/m0/f0");
  ASSERT_GE(g, 0);
  EXPECT_DOUBLE_EQ(m->geom_friction[3 * g], 0.4);
  // plastic/ground is an explicit pair per robot geom that collides.
  ASSERT_GT(m->npair, 0);
  const int terrain = mj_name2id(m.get(), mjOBJ_GEOM, "scene/terrain");
  int with_terrain = 0;
  for (int p = 0; p < m->npair; ++p) {
    if (m->pair_geom1[p] == terrain || m->pair_geom2[p] == terrain) {
      ++with_terrain;
      EXPECT_DOUBLE_EQ(m->pair_friction[5 * p], 0.6);
    }
  }
  const int colliding = testing::CollidingRobotGeoms(m.get());
  // 22 frames (9 flush locked pairs of them share one box), 2 sensor
  // modules, 2 plates.
  EXPECT_EQ(colliding, 22 - 9 + 2 + 2);
  EXPECT_EQ(with_terrain, colliding);
  // Restitution 0 is critically damped; stiff plastic is as stiff as safe.
  const Eigen::Vector2d solref = ContactSolref(s.contact_frictions[0]);
  EXPECT_DOUBLE_EQ(solref.y(), 1.0);
  EXPECT_DOUBLE_EQ(solref.x(), 0.004);
  ContactFriction bouncy{"a", "b", 0.5, 0.5, 1e4};
  const Eigen::Vector2d soft = ContactSolref(bouncy);
  EXPECT_LT(soft.y(), 1.0);
  EXPECT_GT(soft.x(), 0.004);
}

TEST(MjcfBuilder, FlushLockedFramesTouchTheGroundAsOneBox) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 11;
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  const mjModel* m = physics.model();
  // The two end frames, and one box for each locked pair between modules.
  EXPECT_EQ(testing::CollidingRobotGeoms(m), 2 + 10);
  // The shared boxes are hidden and weigh nothing: the robot weighs what
  // its modules do, and every frame is still drawn.
  EXPECT_NEAR(mj_getTotalmass(m), 11 * options.module_mass, 1e-12);
  int shared = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_group[g] != kMjcfContactGroup) continue;
    ++shared;
    EXPECT_EQ(m->geom_type[g], mjGEOM_BOX);
    EXPECT_NEAR(m->geom_size[3 * g], 0.05, 1e-12);  // two 5 cm frames long
  }
  EXPECT_EQ(shared, 10);
  for (int i = 0; i < 11; ++i) {
    for (int f = 0; f < 2; ++f) {
      const int g = mj_name2id(m, mjOBJ_GEOM,
                               mjcf_names::FrameBody("snake", i, f).c_str());
      ASSERT_GE(g, 0);
      EXPECT_LT(m->geom_group[g], 3);
    }
  }
  // Lying flat, each box touches down at its four corners.
  physics.Step(250);
  EXPECT_EQ(physics.data()->ncon, 4 * 12);
}

TEST(MjcfBuilder, FramesOfPassiveWheelModulesKeepTheirOwnContacts) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(MakeChain(ChainOptions{}));
  s.robots[0].modules[3].passive_wheels = true;
  Physics physics(s);
  // Module 3's frames steer friction by their own axes: neither joins its
  // neighbour's frame.
  EXPECT_EQ(testing::CollidingRobotGeoms(physics.model()), 2 + 10 + 2);
}

TEST(MjcfBuilder, ContactTimeConstantsDoNotDependOnTheStep) {
  Scenario coarse = SnakeScenario();
  Scenario fine = coarse;
  fine.settings.timestep = 0.0005;
  const std::string dir = TempDir("mjcf_contact_step");
  MjModelPtr a = Load(WriteFile(dir + "/coarse.xml", BuildMjcf(coarse)));
  MjModelPtr b = Load(WriteFile(dir + "/fine.xml", BuildMjcf(fine)));
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->npair, b->npair);
  ASSERT_GT(a->npair, 0);
  for (int p = 0; p < a->npair; ++p) {
    EXPECT_EQ(a->pair_solref[2 * p], b->pair_solref[2 * p]);
  }
  for (int g = 0; g < a->ngeom; ++g) {
    EXPECT_EQ(a->geom_solref[2 * g], b->geom_solref[2 * g]);
  }
}

// A chain of `modules` with one more lock, "loop", from module 0's front
// frame to frame `frame` of the last module: it closes a loop.
Scenario ChainWithLoopLock(int modules, int frame) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = modules;
  Robot robot = MakeChain(options);
  Joint extra;
  extra.guid = "loop";
  extra.type = JointType::kLock;
  extra.left_frame_guid = robot.modules[0].frames[0].guid;
  extra.right_frame_guid = robot.modules[modules - 1].frames[frame].guid;
  robot.locks.push_back(extra);
  s.robots.push_back(robot);
  return s;
}

TEST(MjcfBuilder, LockThatClosesALoopBecomesAWeld) {
  const Scenario s = ChainWithLoopLock(2, 1);
  const std::string xml = BuildMjcf(s);
  EXPECT_NE(xml.find("<weld name=\"snake/weld/loop\""), std::string::npos);
  Physics physics(s);
  EXPECT_EQ(physics.model()->neq, 1);
}

TEST(MjcfBuilder, AContactBoxNeverTouchesWhatItsFramesMustNot) {
  // A lock from module 0 to module 2's front frame closes a loop (a weld).
  // That frame shares its contact box with module 1's back frame, in
  // module 1's body, so the box must not touch module 0 either.
  const Scenario s = ChainWithLoopLock(3, 0);
  const std::string xml = BuildMjcf(s);
  EXPECT_NE(xml.find("<geom name=\"snake/m1/f1/contact\""), std::string::npos);
  EXPECT_NE(xml.find("<exclude body1=\"snake/m0/f0\" body2=\"snake/m2/f0\""),
            std::string::npos);
  EXPECT_NE(xml.find("<exclude body1=\"snake/m0/f0\" body2=\"snake/m1/f1\""),
            std::string::npos);
  Physics physics(s);
  physics.Step(50);
}

TEST(MjcfBuilder, HingeThatClosesALoopIsRejected) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 2;
  Robot robot = MakeChain(options);
  Joint extra;
  extra.guid = "bad";
  extra.type = JointType::kHinge;
  // A second hinge between the two frames of module 0.
  extra.left_frame_guid = robot.modules[0].frames[0].guid;
  extra.right_frame_guid = robot.modules[0].frames[1].guid;
  robot.locks.push_back(extra);
  s.robots.push_back(robot);
  try {
    BuildMjcf(s);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'bad'"), std::string::npos)
        << e.what();
  }
}

TEST(MjcfBuilder, UnreadableMeshIsNamed) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 1;
  Robot robot = MakeChain(options);
  robot.modules[0].frames[1].shape = "meshes/missing.stl";
  s.robots.push_back(robot);
  s.base_dir = "/nonexistent";
  try {
    BuildMjcf(s);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/meshes/missing.stl"),
              std::string::npos)
        << e.what();
  }
}

TEST(MjcfBuilder, MeshFrameUsesAbsolutePathAndScale) {
  const std::string dir = TempDir("mjcf_mesh");
  // A unit cube as ASCII STL is awkward; OBJ is simple.
  std::ofstream(dir + "/cube.obj")
      << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
         "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
         "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  Scenario s = testing::FlatScenario();
  s.base_dir = dir;
  ChainOptions options;
  options.modules = 1;
  Robot robot = MakeChain(options);
  robot.modules[0].frames[1].shape = "cube.obj";
  robot.modules[0].frames[1].scale = Eigen::Vector3d(0.025, 0.025, 0.025);
  s.robots.push_back(robot);
  const std::string xml = BuildMjcf(s);
  EXPECT_NE(xml.find("file=\"" + dir + "/cube.obj\""), std::string::npos)
      << xml;
  Physics physics(s);
  const mjModel* m = physics.model();
  ASSERT_EQ(m->nmesh, 1);
  const int g = mj_name2id(m, mjOBJ_GEOM, "snake/m0/f1");
  ASSERT_GE(g, 0);
  EXPECT_EQ(m->geom_type[g], mjGEOM_MESH);
  EXPECT_NEAR(m->geom_rbound[g], 0.025 * std::sqrt(3.0), 1e-6);
}

TEST(MjcfBuilder, ExportedHeightFieldMatchesTheImage) {
  const std::string dir = TempDir("mjcf_hfield");
  Scenario s = testing::FlatScenario();
  s.base_dir = dir;
  testing::WriteGreyPng(dir + "/hills.png", 6, 8,
                        [](int r, int c) { return 20 + 10 * r + 3 * c; });
  s.scene.height_image = "hills.png";
  s.scene.height = 0.3;
  s.scene.meters_per_pixel = 0.1;
  const std::string xml = BuildMjcf(s);
  EXPECT_NE(xml.find("file=\"" + dir + "/hills.png\""), std::string::npos);
  MjModelPtr exported = Load(WriteFile(dir + "/scene.xml", xml));
  ASSERT_TRUE(exported);
  Physics physics(s);
  const mjModel* m = physics.model();
  ASSERT_EQ(m->nhfield, 1);
  ASSERT_EQ(exported->hfield_nrow[0], 6);
  ASSERT_EQ(exported->hfield_ncol[0], 8);
  EXPECT_DOUBLE_EQ(m->hfield_size[0], 0.4);
  EXPECT_DOUBLE_EQ(m->hfield_size[1], 0.3);
  EXPECT_DOUBLE_EQ(m->hfield_size[2], 0.3);
  for (int i = 0; i < 48; ++i) {
    EXPECT_NEAR(m->hfield_data[i], exported->hfield_data[i], 1e-6) << i;
  }
  // Embedded bytes give the same field (exported via a PNG it writes).
  Scenario embedded = s;
  std::ifstream in(dir + "/hills.png", std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  embedded.scene.height_image = "base64:" + Base64Encode(bytes);
  MjcfOptions options;
  options.asset_dir = dir;
  MjModelPtr from_bytes =
      Load(WriteFile(dir + "/embedded.xml", BuildMjcf(embedded, options)));
  ASSERT_TRUE(from_bytes);
  for (int i = 0; i < 48; ++i) {
    EXPECT_NEAR(from_bytes->hfield_data[i], m->hfield_data[i], 1e-6) << i;
  }
}

TEST(MjcfBuilder, UnreadableTerrainImageIsNamed) {
  Scenario s = testing::FlatScenario();
  s.base_dir = "/nonexistent";
  s.scene.height_image = "terrain/none.png";
  try {
    BuildMjcf(s);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("terrain/none.png"), std::string::npos)
        << e.what();
  }
}

TEST(MjcfBuilder, DuplicateRobotNamesAreRejected) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 1;
  s.robots.push_back(MakeChain(options));
  s.robots.push_back(MakeChain(options));
  EXPECT_THROW(BuildMjcf(s), std::runtime_error);
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

TEST(MjcfBuilder, ExportedTerrainIsNamedRelativeToTheFile) {
  // An embedded image and a PNG beside the scenario, exported into another
  // folder: the model and its terrain move together.
  const std::string dir = TempDir("mjcf_relative");
  const std::string out = dir + "/export";
  std::filesystem::create_directories(out);
  Scenario s = testing::FlatScenario();
  s.base_dir = dir;
  testing::WriteGreyPng(dir + "/hills.png", 6, 8,
                        [](int r, int c) { return 20 + 10 * r + 3 * c; });
  std::ifstream in(dir + "/hills.png", std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  s.scene.height = 0.3;
  MjcfOptions options;
  options.file_dir = out;
  for (const std::string& image :
       {std::string("hills.png"), "base64:" + Base64Encode(bytes)}) {
    s.scene.height_image = image;
    const std::string xml = BuildMjcf(s, options);
    EXPECT_EQ(xml.find(dir), std::string::npos) << "an absolute path";
    const size_t at = xml.find("file=\"");
    ASSERT_NE(at, std::string::npos);
    const std::string file =
        xml.substr(at + 6, xml.find('"', at + 6) - (at + 6));
    EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + file)) << file;
    MjModelPtr m = Load(WriteFile(out + "/scene.xml", xml));
    ASSERT_TRUE(m);
    EXPECT_EQ(m->hfield_nrow[0], 6);
  }
}

TEST(MjcfBuilder, EveryKindOfPartHasItsOwnColourAndTheSceneMujocosLook) {
  Scenario s = SnakeScenario();
  s.robots[0].modules[1].axis = Axis::kYaw;
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.position = Eigen::Vector3d(1, 0, 0.1);
  s.scene_objects.push_back(ball);
  const std::string dir = TempDir("mjcf_look");
  MjModelPtr m = Load(WriteFile(dir + "/look.xml", BuildMjcf(s)));
  ASSERT_TRUE(m);
  auto rgba = [&](const std::string& geom) {
    const int g = mj_name2id(m.get(), mjOBJ_GEOM, geom.c_str());
    EXPECT_GE(g, 0) << geom;
    const int mat = m->geom_matid[g];
    EXPECT_GE(mat, 0) << geom;
    return Eigen::Vector3d(m->mat_rgba[4 * mat], m->mat_rgba[4 * mat + 1],
                           m->mat_rgba[4 * mat + 2]);
  };
  const std::vector<Eigen::Vector3d> kinds = {
      rgba("snake/m0/f0"),           // pitch module
      rgba("snake/m1/f0"),           // yaw module
      rgba("snake/sm0"),             // sensor module
      rgba("snake/sm0/force/body"),  // force plate
      rgba("snake/sm0/distance"),    // distance sensor
      rgba("scene/obj0"),            // scene object
  };
  for (size_t a = 0; a < kinds.size(); ++a) {
    for (size_t b = a + 1; b < kinds.size(); ++b) {
      EXPECT_GT((kinds[a] - kinds[b]).norm(), 0.2) << a << " vs " << b;
    }
  }
  // Gradient sky, checker floor.
  bool sky = false, checker = false;
  for (int t = 0; t < m->ntex; ++t) {
    sky |= m->tex_type[t] == mjTEXTURE_SKYBOX;
    checker |= m->tex_type[t] == mjTEXTURE_2D;
  }
  EXPECT_TRUE(sky);
  EXPECT_TRUE(checker);
  const int floor = mj_name2id(m.get(), mjOBJ_GEOM, "scene/terrain");
  ASSERT_GE(floor, 0);
  ASSERT_GE(m->geom_matid[floor], 0);
  EXPECT_GE(m->mat_texid[m->geom_matid[floor]], 0);
  // Distance sensors are MuJoCo rangefinders too.
  const int range = mj_name2id(m.get(), mjOBJ_SENSOR, "snake/sm0/distance");
  ASSERT_GE(range, 0);
  EXPECT_EQ(m->sensor_type[range], mjSENS_RANGEFINDER);
}

TEST(MjcfBuilder, MaterialNamesShadeTheirKindsColour) {
  Scenario s = SnakeScenario();
  s.robots[0].modules[0].frames[0].material_name = "rubber";
  const std::string dir = TempDir("mjcf_shade");
  MjModelPtr m = Load(WriteFile(dir + "/shade.xml", BuildMjcf(s)));
  ASSERT_TRUE(m);
  auto rgb = [&](const char* geom) {
    const int mat = m->geom_matid[mj_name2id(m.get(), mjOBJ_GEOM, geom)];
    return Eigen::Vector3d(m->mat_rgba[4 * mat], m->mat_rgba[4 * mat + 1],
                           m->mat_rgba[4 * mat + 2]);
  };
  const Eigen::Vector3d plastic = rgb("snake/m0/f1");
  const Eigen::Vector3d rubber = rgb("snake/m0/f0");
  EXPECT_NE(plastic, rubber);
  // A shade: the same hue, so the ratios of the channels stay.
  EXPECT_NEAR(plastic.x() / plastic.z(), rubber.x() / rubber.z(), 0.05);
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

// The worlds of a split scene are never drawn: their models leave the
// 4.7 MB of textures out and move exactly as the drawn model does.
TEST(MjcfBuilder, AModelWithoutTexturesMovesTheSame) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(MakeChain(ChainOptions{}));
  MjcfOptions bare;
  bare.textures = false;
  const MjModelPtr drawn = CompileScenarioModel(s, MjcfOptions{});
  const MjModelPtr undrawn = CompileScenarioModel(s, bare);
  EXPECT_GT(drawn->ntex, 0);
  EXPECT_EQ(undrawn->ntex, 0);
  EXPECT_LT(undrawn->nbuffer, drawn->nbuffer / 4);
  const MjDataPtr a(mj_makeData(drawn.get()));
  const MjDataPtr b(mj_makeData(undrawn.get()));
  for (int step = 0; step < 200; ++step) {
    for (int k = 0; k < drawn->nu; ++k) {
      a->ctrl[k] = b->ctrl[k] = 0.4 * std::sin(0.05 * step + k);
    }
    mj_step(drawn.get(), a.get());
    mj_step(undrawn.get(), b.get());
  }
  ASSERT_EQ(drawn->nq, undrawn->nq);
  for (int i = 0; i < drawn->nq; ++i) EXPECT_EQ(a->qpos[i], b->qpos[i]) << i;
}

}  // namespace
}  // namespace mrsim

// A design saved with "Embed terrain and meshes": the file carries its mesh
// and height image, reads back equal and builds where the files are gone;
// a file that cannot be read is named.
#include "sim_core/scenario/embed_assets.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

const char* kCubeObj =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(EmbedAssets, SavedDesignCarriesItsMeshAndTerrainAndRunsWithoutThem) {
  const std::string dir = testing::TempDir("embed_assets_design");
  fs::create_directories(dir + "/assets");
  std::ofstream(dir + "/assets/cube.obj") << kCubeObj;
  fs::copy_file(testing::SourcePath("scenarios/terrain.png"),
                dir + "/assets/terrain.png",
                fs::copy_options::overwrite_existing);
  ChainOptions options;
  options.modules = 3;
  Scenario s;
  s.robots.push_back(MakeChain(options));
  s.robots[0].modules[1].frames[0].shape = "assets/cube.obj";
  s.scene.height_image = "assets/terrain.png";
  s.base_dir = dir;
  EXPECT_TRUE(NamesAssetFiles(s));

  EmbedAssetFiles(s);
  EXPECT_FALSE(NamesAssetFiles(s));  // the studio shows it ticked on reopening
  const std::string& shape = s.robots[0].modules[1].frames[0].shape;
  ASSERT_TRUE(IsEmbeddedMesh(shape));
  const EmbeddedMesh mesh = DecodeEmbeddedMesh(shape);
  EXPECT_EQ(mesh.file_name, "cube.obj");
  EXPECT_EQ(std::string(mesh.bytes.begin(), mesh.bytes.end()), kCubeObj);
  ASSERT_EQ(s.scene.height_image.rfind("base64:", 0), 0u);
  const std::string png = Bytes(dir + "/assets/terrain.png");

  // Saved elsewhere, the files gone: it reads back the same and builds.
  const std::string elsewhere = testing::TempDir("embed_assets_elsewhere");
  WriteScenarioFile(s, elsewhere + "/design.xml");
  fs::remove_all(dir + "/assets");
  const Scenario back = ReadScenarioFile(elsewhere + "/design.xml");
  EXPECT_TRUE(back == s);
  EXPECT_NO_THROW(Physics physics(back));
  // Embedding again changes nothing.
  Scenario again = back;
  EmbedAssetFiles(again);
  EXPECT_TRUE(again == back);
  EXPECT_FALSE(png.empty());
}

TEST(EmbedAssets, AFileThatCannotBeReadIsNamed) {
  ChainOptions options;
  options.modules = 2;
  Scenario s;
  s.robots.push_back(MakeChain(options));
  s.robots[0].modules[0].frames[0].shape = "/nonexistent/wheel.stl";
  try {
    EmbedAssetFiles(s);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(s.robots[0].modules[0].frames[0].guid),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("wheel.stl"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace mrsim

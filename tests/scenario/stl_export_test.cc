// Export for printing: every STL written is a closed surface a slicer
// accepts, at the part's real size, and the parts list counts what the
// robot is made of.
#include "sim_core/export/stl_export.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario_tool/scenario_command.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/mesh/triangle_mesh.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

struct Stl {
  std::vector<std::array<Eigen::Vector3f, 3>> triangles;
};

// Reads a binary STL the way a slicer does; fails the test when the
// triangle count does not match the length.
Stl ParseStl(const std::string& bytes) {
  Stl stl;
  EXPECT_GE(bytes.size(), 84u);
  if (bytes.size() < 84) return stl;
  uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(bytes.size(), 84u + 50u * count);
  if (bytes.size() != 84u + 50u * count) return stl;
  for (uint32_t t = 0; t < count; ++t) {
    const char* p = bytes.data() + 84 + 50 * t + 12;
    std::array<Eigen::Vector3f, 3> tri;
    for (int v = 0; v < 3; ++v) {
      float xyz[3];
      std::memcpy(xyz, p + 12 * v, 12);
      tri[v] = Eigen::Vector3f(xyz[0], xyz[1], xyz[2]);
    }
    stl.triangles.push_back(tri);
  }
  return stl;
}

using Key = std::array<float, 3>;
Key KeyOf(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }

// Every edge shared by exactly two triangles that run it in opposite
// directions (a closed, consistently wound surface), and a positive
// enclosed volume (normals point out). Returns "" or what is wrong.
std::string WatertightProblem(const Stl& stl) {
  std::map<std::pair<Key, Key>, int> directed;
  double volume = 0;
  for (const auto& t : stl.triangles) {
    for (int k = 0; k < 3; ++k) {
      ++directed[{KeyOf(t[k]), KeyOf(t[(k + 1) % 3])}];
    }
    volume += t[0].cast<double>().dot(
                  t[1].cast<double>().cross(t[2].cast<double>())) /
              6.0;
  }
  if (stl.triangles.empty()) return "no triangles";
  for (const auto& [edge, uses] : directed) {
    if (uses != 1) return "an edge runs the same way in two triangles";
    auto back = directed.find({edge.second, edge.first});
    if (back == directed.end()) return "an edge belongs to one triangle only";
  }
  if (!(volume > 0)) return "normals point inwards";
  return "";
}

Eigen::Vector3f SizeOf(const Stl& stl) {
  Eigen::AlignedBox3f box;
  for (const auto& t : stl.triangles) {
    for (const auto& v : t) box.extend(v);
  }
  return box.sizes();
}

const std::string& FileNamed(const StlExport& e, const std::string& name) {
  for (const auto& [file, bytes] : e.files) {
    if (file == name) return bytes;
  }
  ADD_FAILURE() << "no file " << name;
  static const std::string kNone;
  return kNone;
}

Scenario SensorChain() {
  ChainScenarioOptions options;
  options.chain.modules = 4;
  options.chain.sensor_after = SensorsAfter(SensorPlacement::kAll, 4);
  options.chain.force_sensors = true;
  options.chain.front_distance_sensor = true;
  options.chain.frame_size = Eigen::Vector3d(0.05, 0.04, 0.03);
  return MakeChainScenario(options);
}

TEST(StlExport, EveryPartFileIsWatertightAtItsRealSizeInMillimetres) {
  const Scenario s = SensorChain();
  const StlExport e = ExportStl(s);
  std::map<std::string, Eigen::Vector3f> expected = {
      {"module frame", Eigen::Vector3f(50, 40, 30)},
      {"sensor module", Eigen::Vector3f(50, 40, 30)},
      {"force plate", Eigen::Vector3f(40, 40, 2)}};
  for (const PrintedPart& part : e.parts) {
    if (part.file.empty()) continue;
    SCOPED_TRACE(part.file);
    const Stl stl = ParseStl(FileNamed(e, part.file));
    EXPECT_EQ(WatertightProblem(stl), "");
    ASSERT_TRUE(expected.count(part.kind));
    EXPECT_TRUE(SizeOf(stl).isApprox(expected[part.kind], 1e-4f))
        << SizeOf(stl).transpose();
  }
}

TEST(StlExport, PartsListCountsEachDistinctPartWithMassAndMaterial) {
  const StlExport e = ExportStl(SensorChain());
  std::map<std::string, int> counts;
  for (const PrintedPart& p : e.parts) counts[p.kind] += p.count;
  EXPECT_EQ(counts["module frame"], 8);
  EXPECT_EQ(counts["sensor module"], 5);
  EXPECT_EQ(counts["force plate"], 5);
  EXPECT_EQ(counts["distance sensor"], 1);
  EXPECT_EQ(e.parts.size(), 4u);  // all frames alike, all modules alike
  const std::string csv = FileNamed(e, "parts.csv");
  EXPECT_THAT(csv, HasSubstr("part,file,count,size_x_mm,size_y_mm,size_z_mm,"
                             "mass_each_kg,mass_total_kg,material\n"));
  EXPECT_THAT(csv, HasSubstr("module_frame_50x40x30mm_plastic,module_frame_"
                             "50x40x30mm_plastic.stl,8,50,40,30,0.05,0.4,"
                             "plastic\n"));
}

TEST(StlExport, AssembledRobotHoldsEveryPrintedPartInItsStartPose) {
  const Scenario s = SensorChain();
  const StlExport e = ExportStl(s);
  const Stl stl = ParseStl(FileNamed(e, "snake_assembled.stl"));
  EXPECT_EQ(stl.triangles.size(), 12u * (8 + 5 + 5));
  // 4 modules of two 50 mm frames and 5 sensor modules of 50 mm in a row,
  // standing on 2 mm plates.
  EXPECT_TRUE(SizeOf(stl).isApprox(Eigen::Vector3f(650, 40, 32), 1e-4f))
      << SizeOf(stl).transpose();
}

TEST(StlExport, MeshFramesAreWrittenAsTheirMeshAtTheirScale) {
  // A unit cube as an ASCII STL, scaled to 20 x 30 x 10 mm by the frame.
  const std::string dir = testing::TempDir("stl_export_mesh");
  Scenario s = MakeChainScenario({});
  const TriangleMesh cube = BoxMesh(Eigen::Vector3d(1, 1, 1));
  {
    std::ofstream out(dir + "/cube.stl", std::ios::binary);
    out << BinaryStl(cube, 1.0, "cube");
  }
  s.base_dir = dir;
  for (Module& m : s.robots[0].modules) {
    m.frames[0].shape = "cube.stl";
    m.frames[0].scale = Eigen::Vector3d(0.02, 0.03, 0.01);
  }
  const StlExport e = ExportStl(s);
  bool found = false;
  for (const PrintedPart& p : e.parts) {
    if (p.name.find("20x30x10mm") == std::string::npos) continue;
    found = true;
    // Named after the mesh its designer drew, not "module_frame_..._2".
    EXPECT_EQ(p.name, "cube_20x30x10mm_" +
                          s.robots[0].modules[0].frames[0].material_name);
    EXPECT_EQ(p.count, 11);
    const Stl stl = ParseStl(FileNamed(e, p.file));
    EXPECT_EQ(WatertightProblem(stl), "");
    EXPECT_TRUE(SizeOf(stl).isApprox(Eigen::Vector3f(20, 30, 10), 1e-3f))
        << SizeOf(stl).transpose();
  }
  EXPECT_TRUE(found);
}

TEST(StlExport, CommandWritesTheFilesOfTheCaseStudyIntoTheDirectory) {
  const std::string dir = testing::TempDir("stl_export_command") + "/out";
  ScenarioCommand command;
  command.action = ScenarioAction::kExportStl;
  command.file = testing::SourcePath("scenarios/case_study.xml");
  command.out_path = dir;
  std::ostringstream out, info;
  RunScenarioCommand(command, out, info);
  EXPECT_THAT(out.str(), HasSubstr("distinct) in " + dir));
  const StlExport e = ExportStl(ReadScenarioFile(command.file));
  for (const auto& [name, bytes] : e.files) {
    SCOPED_TRACE(name);
    std::ifstream in(dir + "/" + name, std::ios::binary);
    ASSERT_TRUE(in.good());
    std::stringstream read;
    read << in.rdbuf();
    EXPECT_EQ(read.str(), bytes);
    if (name.size() > 4 && name.substr(name.size() - 4) == ".stl" &&
        name.find("assembled") == std::string::npos) {
      EXPECT_EQ(WatertightProblem(ParseStl(bytes)), "");
    }
  }
}

TEST(StlExport, ADesignWithoutRobotPartsIsRefused) {
  Scenario s;
  s.scene_objects.push_back(SceneObject{});
  EXPECT_THROW(ExportStl(s), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim

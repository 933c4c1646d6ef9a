#include "sim_core/export/stl_export.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "common/atomic_file.h"
#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/scenario/face_geometry.h"
#include "sim_core/export/frame_mesh.h"
#include "sim_core/mesh/triangle_mesh.h"

namespace mrsim {
namespace {

constexpr double kMillimetres = 1000.0;

// Letters, digits, '-' and '_' only: a robot or material name becomes part
// of a file name and must not climb out of the output directory.
std::string FileSafe(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                    (c >= '0' && c <= '9') || c == '-' || c == '_';
    out.push_back(ok ? c : '_');
  }
  return out.empty() ? "part" : out;
}

std::string Mm(double metres) {
  return fmt::format("{:g}", std::round(metres * kMillimetres * 1000) / 1000);
}

// A mesh part is named after its mesh file ("link.stl", or the name an
// embedded mesh keeps), as the person who drew it knows it; "" for a box.
std::string MeshStem(const std::string& shape) {
  if (shape == "Box") return "";
  const std::string file =
      IsEmbeddedMesh(shape) ? shape.substr(shape.rfind(':') + 1) : shape;
  return std::filesystem::path(file).stem().string();
}

class Exporter {
 public:
  explicit Exporter(const Scenario& s) : s_(s) {}

  // Adds one part instance at `pose` to the assembly `assembly`.
  void Add(const std::string& kind, const std::string& shape,
           const TriangleMesh& local, double mass, const std::string& material,
           const Eigen::Isometry3d& pose, TriangleMesh* assembly,
           bool printed = true) {
    const Eigen::Vector3d size = local.Bounds().sizes();
    const std::string key =
        fmt::format("{}|{}|{:.6f}|{:.6f}|{:.6f}|{:.9g}|{}", kind, shape,
                    size.x(), size.y(), size.z(), mass, material);
    auto it = index_.find(key);
    if (it == index_.end()) {
      PrintedPart part;
      std::string stem = MeshStem(shape);
      if (stem.empty()) {
        stem = kind;
        for (char& c : stem) c = c == ' ' ? '_' : c;
      }
      part.name = FileSafe(fmt::format("{}_{}x{}x{}mm_{}", stem, Mm(size.x()),
                                       Mm(size.y()), Mm(size.z()), material));
      // Same size and material but another shape or mass: numbered.
      const int seen = ++stems_[part.name];
      if (seen > 1) part.name += "_" + std::to_string(seen);
      part.kind = kind;
      part.file = printed ? part.name + ".stl" : "";
      part.size = size;
      part.mass = mass;
      part.material = material;
      it = index_.emplace(key, result_.parts.size()).first;
      result_.parts.push_back(part);
      if (printed) {
        // Centred on its bounding box, so it sits where a slicer puts it.
        TriangleMesh centred;
        Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
        shift.translation() = -local.Bounds().center();
        centred.Append(local, shift);
        result_.files.emplace_back(part.file,
                                   BinaryStl(centred, kMillimetres, part.name));
      }
    }
    ++result_.parts[it->second].count;
    if (printed) assembly->Append(local, pose);
  }

  void AddFrame(const Frame& f, const std::string& kind,
                TriangleMesh* assembly) {
    const std::string key = f.shape + fmt::format("|{}|{}|{}", f.scale.x(),
                                                  f.scale.y(), f.scale.z());
    auto it = meshes_.find(key);
    if (it == meshes_.end()) {
      it = meshes_.emplace(key, FrameMeshSurface(f, s_.base_dir)).first;
    }
    Add(kind, f.is_mesh() ? f.shape : "Box", it->second, f.mass,
        f.material_name, Pose(f.position, f.quat_rotation), assembly);
  }

  void AddSensorModule(const SensorModule& sm, TriangleMesh* assembly) {
    const Eigen::Isometry3d pose = Pose(sm.position, sm.quat_rotation);
    Add("sensor module", "Box", BoxMesh(sm.size), sm.mass, sm.material_name,
        pose, assembly);
    if (sm.force_sensor) {
      const ForceSensor& plate = *sm.force_sensor;
      const PlatePose local = ForcePlatePose(sm);
      Add("force plate", "Box", BoxMesh(plate.size), plate.mass,
          plate.material_name, pose * Pose(local.position, local.rotation),
          assembly);
    }
    for (const DistanceSensor& d : sm.distance_sensors) {
      // A bought sensor: listed, not printed (the physics has no body for
      // it either).
      Add("distance sensor", "Box", BoxMesh(d.size), d.mass, "sensor", pose,
          assembly, false);
    }
  }

  void Finish(const std::string& stem, const TriangleMesh& assembly) {
    if (assembly.faces.empty()) return;
    result_.files.emplace_back(stem + "_assembled.stl",
                               BinaryStl(assembly, kMillimetres, stem));
  }

  StlExport Take() {
    result_.files.emplace_back("parts.csv", PartsListCsv(result_.parts));
    return std::move(result_);
  }

 private:
  static Eigen::Isometry3d Pose(const Eigen::Vector3d& position,
                                const Eigen::Quaterniond& rotation) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rotation.normalized().toRotationMatrix();
    pose.translation() = position;
    return pose;
  }

  const Scenario& s_;
  StlExport result_;
  std::map<std::string, size_t> index_;
  std::map<std::string, int> stems_;
  std::map<std::string, TriangleMesh> meshes_;
};

}  // namespace

StlExport ExportStl(const Scenario& scenario) {
  Exporter exporter(scenario);
  std::map<std::string, int> stems;
  for (size_t r = 0; r < scenario.robots.size(); ++r) {
    const Robot& robot = scenario.robots[r];
    TriangleMesh assembly;
    for (const Module& m : robot.modules) {
      for (const Frame& f : m.frames) {
        exporter.AddFrame(f, "module frame", &assembly);
      }
    }
    for (const SensorModule& sm : robot.sensor_modules) {
      exporter.AddSensorModule(sm, &assembly);
    }
    std::string stem = FileSafe(RobotName(scenario, static_cast<int>(r)));
    if (++stems[stem] > 1) stem += "_" + std::to_string(stems[stem]);
    exporter.Finish(stem, assembly);
  }
  TriangleMesh loose;
  for (const Frame& f : scenario.loose_frames) {
    exporter.AddFrame(f, "loose frame", &loose);
  }
  for (const SensorModule& sm : scenario.loose_sensor_modules) {
    exporter.AddSensorModule(sm, &loose);
  }
  exporter.Finish("loose_parts", loose);
  StlExport result = exporter.Take();
  if (result.parts.empty()) {
    throw std::invalid_argument(
        "the design has no robot parts to print (scene objects and the "
        "terrain are not exported)");
  }
  return result;
}

std::string PartsListCsv(const std::vector<PrintedPart>& parts) {
  std::string out =
      "part,file,count,size_x_mm,size_y_mm,size_z_mm,mass_each_kg,"
      "mass_total_kg,material\n";
  for (const PrintedPart& p : parts) {
    out += fmt::format("{},{},{},{},{},{},{:g},{:g},{}\n", p.name, p.file,
                       p.count, Mm(p.size.x()), Mm(p.size.y()), Mm(p.size.z()),
                       p.mass, p.mass * p.count, FileSafe(p.material));
  }
  return out;
}

void WriteStlExport(const StlExport& result, const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    throw std::runtime_error("cannot make the directory '" + dir +
                             "': " + error.message());
  }
  for (const auto& [name, bytes] : result.files) {
    WriteFileAtomically((std::filesystem::path(dir) / name).string(), bytes);
  }
}

}  // namespace mrsim

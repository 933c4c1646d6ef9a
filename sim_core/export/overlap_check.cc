#include "sim_core/export/overlap_check.h"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <map>
#include <stdexcept>

#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_ptr.h"
#include "sim_core/scenario/scene_object_name.h"

namespace mrsim {
namespace {

struct PartName {
  std::string what;
  std::string path;
};

// "scene object 'ball'" by the name the user gave it
// (scene_object_name.h); the index when it has none.
std::string SceneObjectName(const SceneObject& o, size_t i) {
  const std::string name = SceneObjectGivenName(o);
  if (name.empty()) return fmt::format("scene object {}", i);
  return fmt::format("scene object '{}'", name);
}

// MJCF body name -> the part it models, for every body that can collide.
std::map<std::string, PartName> PartsByBody(const Scenario& s) {
  std::map<std::string, PartName> parts;
  auto add_sensor_modules = [&](const std::string& robot,
                                const std::string& path, const std::string& who,
                                const std::vector<SensorModule>& list) {
    for (size_t k = 0; k < list.size(); ++k) {
      const int i = static_cast<int>(k);
      const std::string sm_path =
          fmt::format("{}/sensorModules/SensorModule[{}]", path, k + 1);
      const std::string sm_what = fmt::format("{}sensor module {}", who, k);
      parts[mjcf_names::SensorModuleBody(robot, i)] = {sm_what, sm_path};
      parts[mjcf_names::PlateBody(robot, i)] = {sm_what + " force plate",
                                                sm_path + "/forceSensor"};
    }
  };
  for (size_t r = 0; r < s.robots.size(); ++r) {
    const std::string robot = RobotName(s, static_cast<int>(r));
    const std::string path = fmt::format("Scenario/robot[{}]", r + 1);
    const std::string who = "robot '" + robot + "' ";
    const Robot& rb = s.robots[r];
    for (size_t i = 0; i < rb.modules.size(); ++i) {
      for (int f = 0; f < 2; ++f) {
        parts[mjcf_names::FrameBody(robot, static_cast<int>(i), f)] = {
            fmt::format("{}module {} {}", who, i, FrameName(f)),
            fmt::format("{}/modules/Module[{}]/frames/Frame[{}]", path, i + 1,
                        f + 1)};
      }
    }
    add_sensor_modules(robot, path, who, rb.sensor_modules);
  }
  for (size_t i = 0; i < s.loose_frames.size(); ++i) {
    parts["loose/f" + std::to_string(i)] = {
        fmt::format("loose frame {}", i),
        fmt::format("Scenario/frames/Frame[{}]", i + 1)};
  }
  add_sensor_modules("loose", "Scenario", "loose ", s.loose_sensor_modules);
  for (size_t i = 0; i < s.scene_objects.size(); ++i) {
    parts[mjcf_names::SceneObject(static_cast<int>(i))] = {
        SceneObjectName(s.scene_objects[i], i),
        fmt::format("Scenario/sceneObjects/SceneObject[{}]", i + 1)};
  }
  parts[mjcf_names::Terrain()] = {"the terrain", "Scenario/scene"};
  return parts;
}

}  // namespace

std::vector<PartOverlap> FindOverlaps(const Scenario& scenario,
                                      double tolerance) {
  MjcfOptions options;
  options.rangefinders = false;
  const MjModelPtr model = CompileScenarioModel(scenario, options);
  return FindOverlapsInModel(scenario, model.get(), tolerance);
}

std::vector<PartOverlap> FindOverlapsInModel(const Scenario& scenario,
                                             const mjModel* m,
                                             double tolerance) {
  MjDataPtr data(mj_makeData(m));
  if (!data) throw std::runtime_error("cannot allocate MuJoCo data");
  // Positions only: kinematics, then MuJoCo's broad and narrow phase with
  // its own filters (parent-child, excluded pairs, contype/conaffinity).
  mj_fwdPosition(m, data.get());

  const std::map<std::string, PartName> parts = PartsByBody(scenario);
  auto name_of = [&](int body) -> std::string {
    const char* name = mj_id2name(m, mjOBJ_BODY, body);
    return name ? name : "";
  };
  auto part_of = [&](int geom) -> PartName {
    // The terrain is a geom of the world body; everything else is named by
    // its body.
    const char* gname = mj_id2name(m, mjOBJ_GEOM, geom);
    if (gname && mjcf_names::Terrain() == gname) {
      return parts.at(mjcf_names::Terrain());
    }
    auto it = parts.find(name_of(m->geom_bodyid[geom]));
    if (it != parts.end()) return it->second;
    return {gname ? gname : "geom " + std::to_string(geom), ""};
  };
  std::map<std::pair<std::string, std::string>, PartOverlap> found;
  for (int c = 0; c < data->ncon; ++c) {
    const mjContact& con = data->contact[c];
    const double depth = -con.dist;
    if (!(depth > tolerance)) continue;
    PartName a = part_of(con.geom1);
    PartName b = part_of(con.geom2);
    std::string body_a = name_of(m->geom_bodyid[con.geom1]);
    std::string body_b = name_of(m->geom_bodyid[con.geom2]);
    // The terrain last, otherwise file order.
    if (b.path != "Scenario/scene" &&
        (a.path == "Scenario/scene" || b.path < a.path)) {
      std::swap(a, b);
      std::swap(body_a, body_b);
    }
    PartOverlap& o = found[{a.path + "|" + a.what, b.path + "|" + b.what}];
    if (depth > o.depth) {
      o = {a.what, b.what, a.path, b.path, body_a, body_b, depth};
    }
  }
  std::vector<PartOverlap> result;
  for (auto& [key, o] : found) result.push_back(o);
  std::stable_sort(result.begin(), result.end(),
                   [](const PartOverlap& x, const PartOverlap& y) {
                     return x.depth > y.depth;
                   });
  return result;
}

std::string DescribeOverlap(const PartOverlap& o,
                            const ScenarioSource* source) {
  const std::string where = source ? fmt::format("{}:{}: ", source->file,
                                                 source->LineOf(o.first_path))
                                   : "";
  return fmt::format("{}{}: {} overlaps {} by {:.1f} mm at the start", where,
                     o.first_path, o.first, o.second, o.depth * 1000);
}

namespace {

void Refuse(std::vector<PartOverlap> overlaps, const ScenarioSource* source) {
  if (overlaps.empty()) return;
  std::string text;
  for (const PartOverlap& o : overlaps) {
    if (!text.empty()) text += "\n";
    text += DescribeOverlap(o, source);
  }
  throw OverlapError(text, std::move(overlaps));
}

}  // namespace

void RefuseOverlaps(const Scenario& scenario, const ScenarioSource* source) {
  Refuse(FindOverlaps(scenario), source);
}

void RefuseOverlapsInModel(const Scenario& scenario, const mjModel* model,
                           const ScenarioSource* source) {
  Refuse(FindOverlapsInModel(scenario, model), source);
}

}  // namespace mrsim

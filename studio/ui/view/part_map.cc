#include "studio/ui/view/part_map.h"

#include <string>

#include "sim_core/mjcf/mjcf_names.h"

namespace mrsim::studio {
namespace {

void MarkBody(const mjModel* m, const std::string& body_name,
              const GeomPart& part, std::vector<GeomPart>* geoms) {
  const int body = mj_name2id(m, mjOBJ_BODY, body_name.c_str());
  if (body < 0) return;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] == body) (*geoms)[g] = part;
  }
}

void MarkGeom(const mjModel* m, const std::string& geom_name,
              const GeomPart& part, std::vector<GeomPart>* geoms) {
  const int g = mj_name2id(m, mjOBJ_GEOM, geom_name.c_str());
  if (g >= 0) (*geoms)[g] = part;
}

}  // namespace

std::vector<GeomPart> MapGeoms(const mjModel* m, const Scenario& s) {
  std::vector<GeomPart> geoms(m->ngeom);
  namespace n = mjcf_names;
  for (int r = 0; r < static_cast<int>(s.robots.size()); ++r) {
    const Robot& robot = s.robots[r];
    const std::string name = n::RobotName(s, r);
    for (int i = 0; i < static_cast<int>(robot.modules.size()); ++i) {
      const Look look = robot.modules[i].axis == Axis::kPitch
                            ? Look::kPitchModule
                            : Look::kYawModule;
      for (int f = 0; f < 2; ++f) {
        MarkBody(m, n::FrameBody(name, i, f),
                 {{SelectionKind::kModule, r, i}, look}, &geoms);
      }
    }
    for (int j = 0; j < static_cast<int>(robot.sensor_modules.size()); ++j) {
      const Selection part{SelectionKind::kSensorModule, r, j};
      MarkBody(m, n::SensorModuleBody(name, j), {part, Look::kSensorModule},
               &geoms);
      MarkBody(m, n::PlateBody(name, j), {part, Look::kForcePlate}, &geoms);
      const auto& rays = robot.sensor_modules[j].distance_sensors;
      for (int k = 0; k < static_cast<int>(rays.size()); ++k) {
        MarkGeom(m, n::DistanceSite(name, j, k), {part, Look::kDistanceSensor},
                 &geoms);
      }
    }
  }
  for (int i = 0; i < static_cast<int>(s.scene_objects.size()); ++i) {
    MarkBody(m, n::SceneObject(i),
             {{SelectionKind::kSceneObject, 0, i}, Look::kObject}, &geoms);
  }
  // Parts without a robot: clicked in the view as in the Design panel.
  const std::string loose = n::LooseRobot();
  for (int i = 0; i < static_cast<int>(s.loose_frames.size()); ++i) {
    MarkBody(m, loose + "/f" + std::to_string(i),
             {{SelectionKind::kLooseFrame, 0, i}, Look::kOther}, &geoms);
  }
  for (int j = 0; j < static_cast<int>(s.loose_sensor_modules.size()); ++j) {
    MarkBody(m, n::SensorModuleBody(loose, j),
             {{SelectionKind::kLooseSensorModule, 0, j}, Look::kSensorModule},
             &geoms);
  }
  MarkGeom(m, n::Terrain(), {{SelectionKind::kScene, 0, 0}, Look::kTerrain},
           &geoms);
  return geoms;
}

std::vector<RaySite> MapRays(const mjModel* m, const Scenario& s) {
  std::vector<RaySite> rays;
  for (int r = 0; r < static_cast<int>(s.robots.size()); ++r) {
    const std::string name = mjcf_names::RobotName(s, r);
    const Robot& robot = s.robots[r];
    for (int j = 0; j < static_cast<int>(robot.sensor_modules.size()); ++j) {
      const auto& sensors = robot.sensor_modules[j].distance_sensors;
      for (int k = 0; k < static_cast<int>(sensors.size()); ++k) {
        const int site = mj_name2id(
            m, mjOBJ_SITE, mjcf_names::DistanceSite(name, j, k).c_str());
        if (site >= 0) {
          rays.push_back({site,
                          sensors[k].max_ray_distance,
                          {SelectionKind::kSensorModule, r, j}});
        }
      }
    }
  }
  return rays;
}

}  // namespace mrsim::studio

#include "studio/ui/view/part_map.h"

#include <algorithm>
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

std::vector<LockSite> MapLocks(const mjModel* m, const Scenario& s) {
  std::vector<LockSite> locks;
  for (int r = 0; r < static_cast<int>(s.robots.size()); ++r) {
    const Robot& robot = s.robots[r];
    const std::string name = mjcf_names::RobotName(s, r);
    // A part's body by its guid; a frame merged into its neighbour (flush
    // boxes) keeps its body name, so every lock finds both ends.
    auto body_of = [&](const std::string& guid) {
      for (int i = 0; i < static_cast<int>(robot.modules.size()); ++i) {
        for (int f = 0; f < 2; ++f) {
          if (robot.modules[i].frames[f].guid == guid) {
            return mj_name2id(m, mjOBJ_BODY,
                              mjcf_names::FrameBody(name, i, f).c_str());
          }
        }
      }
      for (int j = 0; j < static_cast<int>(robot.sensor_modules.size()); ++j) {
        if (robot.sensor_modules[j].guid == guid) {
          return mj_name2id(m, mjOBJ_BODY,
                            mjcf_names::SensorModuleBody(name, j).c_str());
        }
      }
      return -1;
    };
    for (int k = 0; k < static_cast<int>(robot.locks.size()); ++k) {
      const Joint& lock = robot.locks[k];
      LockSite site{body_of(lock.left_frame_guid),
                    body_of(lock.right_frame_guid),
                    {SelectionKind::kLock, r, k}};
      if (site.body_a < 0 || site.body_b < 0) continue;
      for (int g = 0; g < m->ngeom; ++g) {
        if (m->geom_bodyid[g] == site.body_a ||
            m->geom_bodyid[g] == site.body_b) {
          // A box's half height is about 0.6 of its bounding radius.
          site.lift = std::max(site.lift, 0.6 * m->geom_rbound[g]);
        }
      }
      locks.push_back(site);
    }
  }
  return locks;
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

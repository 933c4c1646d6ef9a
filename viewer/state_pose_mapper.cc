#include "viewer/state_pose_mapper.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/mujoco/mujoco_data.h"

namespace mrsim {
namespace {

Eigen::Quaterniond QuatFrom(const mjtNum* wxyz) {
  return Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized();
}

void QuatTo(const Eigen::Quaterniond& q, mjtNum* wxyz) {
  wxyz[0] = q.w();
  wxyz[1] = q.x();
  wxyz[2] = q.y();
  wxyz[3] = q.z();
}

bool Finite(const mrsim::Pose& pose) {
  return pose.position.allFinite() && pose.orientation.coeffs().allFinite() &&
         pose.orientation.coeffs().norm() > 1e-9;
}

// Body id of a part: the body BuildMjcf names `mjcf_name`, else a body
// named `guid`, else the body of a geom named `guid` (then geom_pos/quat are
// the geom's pose in its body).
int FindBody(const mjModel* m, const std::string& mjcf_name,
             const std::string& guid, bool* via_geom, Eigen::Vector3d* geom_pos,
             Eigen::Quaterniond* geom_quat) {
  *via_geom = false;
  if (!mjcf_name.empty()) {
    const int body = mj_name2id(m, mjOBJ_BODY, mjcf_name.c_str());
    if (body > 0) return body;
  }
  if (guid.empty()) return -1;
  const int body = mj_name2id(m, mjOBJ_BODY, guid.c_str());
  if (body > 0) return body;
  const int geom = mj_name2id(m, mjOBJ_GEOM, guid.c_str());
  if (geom >= 0 && m->geom_bodyid[geom] > 0) {
    *via_geom = true;
    *geom_pos = Eigen::Vector3d(m->geom_pos + 3 * geom);
    *geom_quat = QuatFrom(m->geom_quat + 4 * geom);
    return m->geom_bodyid[geom];
  }
  return -1;
}

// The site a distance sensor's ray starts from (BuildMjcf: at the face
// centre, x axis along the ray), else a site or rangefinder named after it.
int FindRaySite(const mjModel* m, const std::string& mjcf_name,
                const std::string& guid, int* axis) {
  *axis = 0;
  const int named = mj_name2id(m, mjOBJ_SITE, mjcf_name.c_str());
  if (named >= 0) return named;
  *axis = 2;  // MuJoCo's rangefinder looks along the site's z axis
  if (guid.empty()) return -1;
  const int site = mj_name2id(m, mjOBJ_SITE, guid.c_str());
  if (site >= 0) return site;
  const int sensor = mj_name2id(m, mjOBJ_SENSOR, guid.c_str());
  if (sensor >= 0 && m->sensor_type[sensor] == mjSENS_RANGEFINDER &&
      m->sensor_objtype[sensor] == mjOBJ_SITE) {
    return m->sensor_objid[sensor];
  }
  return -1;
}

}  // namespace

StatePoseMapper::StatePoseMapper(const mjModel* model, const Scenario& scenario)
    : model_(model) {
  if (model == nullptr) throw std::invalid_argument("StatePoseMapper: null");
  const mjModel* m = model;
  const MjDataPtr data = MakeMjData(m);
  if (data == nullptr) throw std::runtime_error("viewer: mj_makeData failed");
  mj_kinematics(m, data.get());
  built_.resize(m->nbody);
  for (int b = 0; b < m->nbody; ++b) {
    built_[b].p = Eigen::Vector3d(data->xpos + 3 * b);
    built_[b].q = QuatFrom(data->xquat + 4 * b);
  }
  sources_.assign(m->nbody, BodySource());

  auto inverse = [](const Pose& a) {
    Pose r;
    r.q = a.q.conjugate();
    r.p = -(r.q * a.p);
    return r;
  };
  auto compose = [](const Pose& a, const Pose& b) {
    Pose r;
    r.p = a.p + a.q * b.p;
    r.q = a.q * b.q;
    return r;
  };

  std::vector<std::pair<int, int>> attach_by_name;  // body, anchor body
  for (size_t r = 0; r < scenario.robots.size(); ++r) {
    const Robot& robot = scenario.robots[r];
    RobotInfo info;
    info.name = mjcf_names::RobotName(scenario, static_cast<int>(r));
    info.modules = static_cast<int>(robot.modules.size());
    info.sensor_modules = static_cast<int>(robot.sensor_modules.size());
    auto map_part = [&](const std::string& mjcf_name, const std::string& guid,
                        int part, const std::string& what) {
      bool via_geom = false;
      Eigen::Vector3d gpos;
      Eigen::Quaterniond gquat;
      const int body = FindBody(m, mjcf_name, guid, &via_geom, &gpos, &gquat);
      if (body < 0) {
        throw std::runtime_error("viewer: robot '" + robot.name + "' " + what +
                                 " '" + guid +
                                 "' has no body or geom of that name in the "
                                 "model built from the scenario");
      }
      BodySource& src = sources_[body];
      if (src.kind == BodySource::kState) return body;  // merged parts
      src.kind = BodySource::kState;
      src.robot = static_cast<int>(r);
      src.part = part;
      if (via_geom) {
        Pose geom_local;
        geom_local.p = gpos;
        geom_local.q = gquat;
        src.offset = inverse(geom_local);
      }
      return body;
    };
    for (int i = 0; i < info.modules; ++i) {
      for (int f = 0; f < 2; ++f) {
        map_part(mjcf_names::FrameBody(info.name, i, f),
                 robot.modules[i].frames[f].guid, 2 * i + f,
                 "module " + std::to_string(i) + " frame " + std::to_string(f));
      }
    }
    for (int s = 0; s < info.sensor_modules; ++s) {
      const SensorModule& sm = robot.sensor_modules[s];
      const int sm_body =
          map_part(mjcf_names::SensorModuleBody(info.name, s), sm.guid,
                   2 * info.modules + s, "sensor module " + std::to_string(s));
      // Plates and distance sensors ride on their sensor module.
      auto attach = [&](const std::string& mjcf_name, const std::string& guid) {
        bool via_geom = false;
        Eigen::Vector3d gpos;
        Eigen::Quaterniond gquat;
        const int body = FindBody(m, mjcf_name, guid, &via_geom, &gpos, &gquat);
        if (body > 0) attach_by_name.emplace_back(body, sm_body);
      };
      if (sm.force_sensor) {
        attach(mjcf_names::PlateBody(info.name, s), sm.force_sensor->guid);
      }
      // Built pose of the sensor module's frame for the fallback rays.
      Pose sm_pose;
      sm_pose.p = sm.position;
      sm_pose.q = sm.quat_rotation.normalized();
      for (size_t k = 0; k < sm.distance_sensors.size(); ++k) {
        const DistanceSensor& ds = sm.distance_sensors[k];
        attach("", ds.guid);
        RaySource ray;
        ray.sensor_module = s;
        ray.index = static_cast<int>(k);
        ray.site = FindRaySite(
            m, mjcf_names::DistanceSite(info.name, s, static_cast<int>(k)),
            ds.guid, &ray.site_axis);
        ray.local_origin = sm_pose.q.conjugate() * (ds.position - sm.position);
        ray.local_direction =
            ds.ray_direction.norm() > 1e-12
                ? Eigen::Vector3d(ds.ray_direction.normalized())
                : Eigen::Vector3d::UnitX();
        ray.max_distance = ds.max_ray_distance;
        info.rays.push_back(ray);
      }
    }
    robots_.push_back(info);
  }

  // Movable scene objects, posed by scene states; what hangs below them in
  // the tree rides along (kAttached below).
  scene_bodies_.assign(scenario.scene_objects.size(), -1);
  for (size_t i = 0; i < scenario.scene_objects.size(); ++i) {
    if (scenario.scene_objects[i].is_static) continue;
    const int body = mj_name2id(
        m, mjOBJ_BODY, mjcf_names::SceneObject(static_cast<int>(i)).c_str());
    if (body <= 0 || sources_[body].kind != BodySource::kBuilt) continue;
    sources_[body].kind = BodySource::kScene;
    sources_[body].part = static_cast<int>(i);
    scene_bodies_[i] = body;
  }

  // Loose frames and sensor modules, posed by the loose state (frames,
  // then sensor modules, as for a robot); their plates ride along.
  loose_frames_ = static_cast<int>(scenario.loose_frames.size());
  loose_sensor_modules_ =
      static_cast<int>(scenario.loose_sensor_modules.size());
  const std::string loose = mjcf_names::LooseRobot();
  auto map_loose = [&](const std::string& name, int part) {
    const int body = mj_name2id(m, mjOBJ_BODY, name.c_str());
    if (body <= 0 || sources_[body].kind != BodySource::kBuilt) return -1;
    sources_[body].kind = BodySource::kLoose;
    sources_[body].part = part;
    return body;
  };
  for (int i = 0; i < loose_frames_; ++i) {
    map_loose(loose + "/f" + std::to_string(i), i);  // as the builder names it
  }
  for (int k = 0; k < loose_sensor_modules_; ++k) {
    const int body =
        map_loose(mjcf_names::SensorModuleBody(loose, k), loose_frames_ + k);
    const int plate =
        mj_name2id(m, mjOBJ_BODY, mjcf_names::PlateBody(loose, k).c_str());
    if (body > 0 && plate > 0) attach_by_name.emplace_back(plate, body);
  }

  // Everything else that moves with a robot: bodies below a state body in
  // the tree, then named plates and sensors welded to a sensor module.
  auto posed = [&](int b) {
    return sources_[b].kind == BodySource::kState ||
           sources_[b].kind == BodySource::kScene ||
           sources_[b].kind == BodySource::kLoose;
  };
  for (int b = 1; b < m->nbody; ++b) {
    if (posed(b)) continue;
    for (int a = m->body_parentid[b]; a > 0; a = m->body_parentid[a]) {
      if (posed(a)) {
        sources_[b].kind = BodySource::kAttached;
        sources_[b].anchor = a;
        sources_[b].offset = compose(inverse(built_[a]), built_[b]);
        break;
      }
    }
  }
  for (const auto& [body, anchor] : attach_by_name) {
    if (sources_[body].kind != BodySource::kBuilt || anchor <= 0) continue;
    sources_[body].kind = BodySource::kAttached;
    sources_[body].anchor = anchor;
    sources_[body].offset = compose(inverse(built_[anchor]), built_[body]);
  }
}

const std::string& StatePoseMapper::robot_name(int robot) const {
  return robots_.at(robot).name;
}

int StatePoseMapper::robot_index(const std::string& name) const {
  for (size_t r = 0; r < robots_.size(); ++r) {
    if (robots_[r].name == name) return static_cast<int>(r);
  }
  return -1;
}

std::string StatePoseMapper::Check(int robot, const RobotState& state) const {
  if (robot < 0 || robot >= robot_count()) return "unknown robot";
  const RobotInfo& info = robots_[robot];
  if (static_cast<int>(state.frames.size()) != 2 * info.modules) {
    return "robot '" + info.name + "': " + std::to_string(state.frames.size()) +
           " frames, expected " + std::to_string(2 * info.modules);
  }
  if (static_cast<int>(state.sensor_modules.size()) != info.sensor_modules) {
    return "robot '" + info.name +
           "': " + std::to_string(state.sensor_modules.size()) +
           " sensor modules, expected " + std::to_string(info.sensor_modules);
  }
  if (!std::isfinite(state.time)) return "non-finite time";
  for (const auto& f : state.frames) {
    if (!Finite(f)) return "non-finite or zero-quaternion frame pose";
  }
  for (const auto& sm : state.sensor_modules) {
    if (!Finite(sm.pose)) return "non-finite sensor module pose";
    for (double dist : sm.distances) {
      if (!std::isfinite(dist)) return "non-finite distance";
    }
  }
  if (!state.com.allFinite() || !state.com_velocity.allFinite()) {
    return "non-finite centre of mass";
  }
  return "";
}

std::string StatePoseMapper::CheckScene(
    const std::vector<SceneObjectState>& scene) const {
  std::vector<bool> seen(scene_bodies_.size(), false);
  for (const SceneObjectState& o : scene) {
    if (o.index < 0 || o.index >= static_cast<int>(scene_bodies_.size())) {
      return "scene object " + std::to_string(o.index) +
             " is not in the scenario (" +
             std::to_string(scene_bodies_.size()) + " scene objects)";
    }
    if (scene_bodies_[o.index] < 0) {
      return "scene object " + std::to_string(o.index) + " is static";
    }
    if (seen[o.index]) {
      return "scene object " + std::to_string(o.index) + " listed twice";
    }
    seen[o.index] = true;
    if (!Finite(o.pose)) {
      return "scene object " + std::to_string(o.index) +
             ": non-finite or zero-quaternion pose";
    }
  }
  return "";
}

std::string StatePoseMapper::CheckLoose(const RobotState& loose) const {
  if (static_cast<int>(loose.frames.size()) != loose_frames_ ||
      static_cast<int>(loose.sensor_modules.size()) != loose_sensor_modules_) {
    return "loose parts: " + std::to_string(loose.frames.size()) +
           " frames and " + std::to_string(loose.sensor_modules.size()) +
           " sensor modules, expected " + std::to_string(loose_frames_) +
           " and " + std::to_string(loose_sensor_modules_);
  }
  if (!std::isfinite(loose.time)) return "non-finite time";
  for (const auto& f : loose.frames) {
    if (!Finite(f)) return "non-finite or zero-quaternion frame pose";
  }
  for (const auto& sm : loose.sensor_modules) {
    if (!Finite(sm.pose)) return "non-finite sensor module pose";
  }
  return "";
}

void StatePoseMapper::Apply(const std::vector<const RobotState*>& states,
                            mjData* d,
                            const std::vector<SceneObjectState>* scene,
                            const RobotState* loose) const {
  const mjModel* m = model_;
  std::vector<Pose> pose(built_);
  auto state_part_pose = [](const RobotState& s, int part) {
    const int frames = static_cast<int>(s.frames.size());
    const mrsim::Pose& src =
        part < frames ? s.frames[part] : s.sensor_modules[part - frames].pose;
    Pose r;
    r.p = src.position;
    r.q = src.orientation.normalized();
    return r;
  };
  auto part_pose = [&](int robot, int part) {
    return state_part_pose(*states[robot], part);
  };
  auto compose = [](const Pose& a, const Pose& b) {
    Pose r;
    r.p = a.p + a.q * b.p;
    r.q = a.q * b.q;
    return r;
  };
  auto has_state = [&](int robot) {
    return robot >= 0 && robot < static_cast<int>(states.size()) &&
           states[robot] != nullptr;
  };
  for (int b = 1; b < m->nbody; ++b) {
    const BodySource& src = sources_[b];
    if (src.kind == BodySource::kState && has_state(src.robot)) {
      pose[b] = compose(part_pose(src.robot, src.part), src.offset);
    } else if (src.kind == BodySource::kLoose && loose != nullptr) {
      pose[b] = state_part_pose(*loose, src.part);
    }
  }
  std::vector<bool> scene_posed(m->nbody, false);
  if (scene != nullptr) {
    for (const SceneObjectState& o : *scene) {
      if (o.index < 0 || o.index >= static_cast<int>(scene_bodies_.size())) {
        continue;
      }
      const int b = scene_bodies_[o.index];
      if (b <= 0) continue;
      pose[b].p = o.pose.position;
      pose[b].q = o.pose.orientation.normalized();
      scene_posed[b] = true;
    }
  }
  for (int b = 1; b < m->nbody; ++b) {
    const BodySource& src = sources_[b];
    if (src.kind != BodySource::kAttached) continue;
    const BodySource& anchor = sources_[src.anchor];
    if ((anchor.kind == BodySource::kState && has_state(anchor.robot)) ||
        (anchor.kind == BodySource::kScene && scene_posed[src.anchor]) ||
        (anchor.kind == BodySource::kLoose && loose != nullptr)) {
      pose[b] = compose(pose[src.anchor], src.offset);
    }
  }
  for (int b = 0; b < m->nbody; ++b) {
    mju_copy3(d->xpos + 3 * b, pose[b].p.data());
    QuatTo(pose[b].q, d->xquat + 4 * b);
    mju_quat2Mat(d->xmat + 9 * b, d->xquat + 4 * b);
  }
  // Geoms, sites and inertial frames sit at fixed offsets in their body,
  // placed as mj_kinematics places them.
  const auto place = [d](int b, const mjtNum* local_pos,
                         const mjtNum* local_quat, mjtNum* pos, mjtNum* mat) {
    mjtNum quat[4];
    mjtNum vec[3];
    mju_mulMatVec(vec, d->xmat + 9 * b, local_pos, 3, 3);
    mju_add3(pos, d->xpos + 3 * b, vec);
    mju_mulQuat(quat, d->xquat + 4 * b, local_quat);
    mju_quat2Mat(mat, quat);
  };
  for (int g = 0; g < m->ngeom; ++g) {
    place(m->geom_bodyid[g], m->geom_pos + 3 * g, m->geom_quat + 4 * g,
          d->geom_xpos + 3 * g, d->geom_xmat + 9 * g);
  }
  for (int s = 0; s < m->nsite; ++s) {
    place(m->site_bodyid[s], m->site_pos + 3 * s, m->site_quat + 4 * s,
          d->site_xpos + 3 * s, d->site_xmat + 9 * s);
  }
  for (int b = 0; b < m->nbody; ++b) {
    place(b, m->body_ipos + 3 * b, m->body_iquat + 4 * b, d->xipos + 3 * b,
          d->ximat + 9 * b);
  }
  // Lights and model cameras follow their bodies as in mj_forward.
  mj_camlight(m, d);
}

std::vector<Ray> StatePoseMapper::Rays(int robot, const RobotState& state,
                                       const mjData* d) const {
  std::vector<Ray> rays;
  if (robot < 0 || robot >= robot_count()) return rays;
  for (const RaySource& src : robots_[robot].rays) {
    if (src.sensor_module >= static_cast<int>(state.sensor_modules.size())) {
      continue;
    }
    const SensorModuleState& sm = state.sensor_modules[src.sensor_module];
    if (src.index >= static_cast<int>(sm.distances.size())) continue;
    double distance = sm.distances[src.index];
    Ray ray;
    ray.hit = distance >= 0.0 && distance < src.max_distance - 1e-9;
    if (!ray.hit) distance = src.max_distance;
    Eigen::Vector3d direction;
    if (src.site >= 0) {
      const mjtNum* xmat = d->site_xmat + 9 * src.site;
      const int a = src.site_axis;
      ray.from = Eigen::Vector3d(d->site_xpos + 3 * src.site);
      direction = Eigen::Vector3d(xmat[a], xmat[3 + a], xmat[6 + a]);
    } else {
      const Eigen::Quaterniond q = sm.pose.orientation.normalized();
      ray.from = sm.pose.position + q * src.local_origin;
      direction = q * src.local_direction;
    }
    ray.to = ray.from + distance * direction;
    rays.push_back(ray);
  }
  return rays;
}

}  // namespace mrsim

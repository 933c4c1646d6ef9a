#include "sim_core/mjcf/mjcf_builder.h"

#include <fmt/format.h>
#include <stb/stb_image_write.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <queue>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/hash.h"
#include "sim_core/mesh/box_union.h"
#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/mjcf/contact_model.h"
#include "sim_core/scenario/face_geometry.h"
#include "sim_core/scenario/part_look.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/sensor_kind.h"
#include "sim_core/scenario/terrain.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;
using Eigen::Quaterniond;
using Eigen::Vector3d;

// ---------------------------------------------------------------- text

std::string Num(double v) {
  if (v == 0) return "0";  // no "-0"
  return fmt::format("{}", v);
}
std::string Vec(const Vector3d& v) {
  return Num(v.x()) + " " + Num(v.y()) + " " + Num(v.z());
}
std::string Quat(const Quaterniond& q) {
  return Num(q.w()) + " " + Num(q.x()) + " " + Num(q.y()) + " " + Num(q.z());
}
Quaterniond Normalized(const Quaterniond& q) {
  const double n = q.norm();
  if (!(n > 0) || !std::isfinite(n)) return Quaterniond::Identity();
  return Quaterniond(q.coeffs() / n);
}

// ---------------------------------------------------------------- look

const char* KindName(PartLook kind) {
  switch (kind) {
    case PartLook::kPitchModule:
      return "pitch_module";
    case PartLook::kYawModule:
      return "yaw_module";
    case PartLook::kLooseFrame:
      return "frame";
    case PartLook::kSensorModule:
      return "sensor_module";
    case PartLook::kForcePlate:
      return "force_plate";
    case PartLook::kDistanceSensor:
      return "distance_sensor";
    case PartLook::kSceneObject:
      return "scene_object";
  }
  return "part";
}

// The MuJoCo material of a kind and scenario material: "<kind>/<material>";
// the material name picks a shade of the kind's colour (0.7x to 1.15x).
std::string LookName(PartLook kind, const std::string& material) {
  return std::string(KindName(kind)) + "/" + material;
}
Eigen::Vector3d LookRgb(PartLook kind, const std::string& material) {
  uint32_t h = 2166136261u;
  for (char c : material) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  const double shade = 0.7 + 0.45 * ((h >> 8) % 1000) / 999.0;
  return (PartLookRgb(kind) * shade).cwiseMin(1.0);
}

// ---------------------------------------------------------------- model

struct GeomSpec {
  std::string name;
  std::string type;                  // box, sphere, capsule, cylinder, mesh
  Vector3d size = Vector3d::Zero();  // MuJoCo size parameters
  Vector3d pos = Vector3d::Zero();   // in the body frame
  Quaterniond quat = Quaterniond::Identity();
  double mass = 0;
  std::string material;
  std::string mesh;  // mesh asset name
  bool collide = true;
  PartLook kind = PartLook::kSceneObject;
  // A module frame's box that may share one contact box with a flush frame
  // locked to it (MergeFlushFrames).
  bool mergeable = false;
  // Collides and weighs nothing; hidden (kMjcfContactGroup).
  bool contact_only = false;
};

struct SiteSpec {
  std::string name;
  Vector3d pos = Vector3d::Zero();
  Quaterniond quat = Quaterniond::Identity();
  bool rangefinder = false;  // a ray along its z axis, export only
  // A marker site (display only, no physics): its MuJoCo type, size
  // parameters and colour; an empty type is the small default sphere.
  std::string type = "";
  Vector3d size = Vector3d::Zero();
  std::string rgba = "";
};

// A fixed MuJoCo camera on a body (a kCamera sensor), in the body's frame.
struct CameraSpec {
  std::string name;
  Vector3d pos = Vector3d::Zero();
  Quaterniond quat = Quaterniond::Identity();
  double fovy = 45;  // deg
};

// An element with attributes, e.g. an asset.
struct ElementSpec {
  std::string tag;
  MjcfAttributes attrs;
};

enum class JointKind { kNone, kFree, kHinge };

struct BodySpec {
  std::string name;
  Vector3d pos = Vector3d::Zero();  // world
  Quaterniond quat = Quaterniond::Identity();
  int parent = -1;  // -1: world
  std::vector<int> children;
  JointKind joint = JointKind::kNone;
  std::string joint_name;
  Vector3d axis = Vector3d::UnitY();   // body frame
  Vector3d anchor = Vector3d::Zero();  // body frame
  double lower = 0, upper = 0;
  std::vector<GeomSpec> geoms;
  std::vector<SiteSpec> sites;
  std::vector<CameraSpec> cameras;
};

struct ActuatorSpec {
  std::string name, joint;
  double max_vel = 0, kv = 0, max_torque = 0;
};

struct WeldSpec {
  std::string name, body1, body2;  // body2 empty: the world
};

// One part of a robot before the tree is known.
struct Node {
  std::string guid;
  std::string what;  // for error messages
  int body = -1;     // index in bodies once placed
  bool is_static = false;
};

struct Edge {
  int a = -1, b = -1;  // node indices; for a hinge a = left, b = right
  bool hinge = false;
  Vector3d axis_world = Vector3d::UnitY();
  Vector3d anchor_world = Vector3d::Zero();
  std::string joint_name, actuator_name, guid;
  double lower = 0, upper = 0, max_vel = 0, kv = 0, max_torque = 0;
  bool servo = false;
  std::string lock;   // lock name (MjcfLock::name); empty for hinges
  bool weld = false;  // a weld equality even where a tree link would do
};

class Builder {
 public:
  Builder(const Scenario& scenario, const MjcfOptions& options, MjcfInfo* info)
      : s_(scenario), options_(options), info_(info) {}

  std::string Build();

 private:
  int AddBody(const std::string& name, const Vector3d& pos,
              const Quaterniond& quat) {
    BodySpec b;
    b.name = name;
    b.pos = pos;
    b.quat = Normalized(quat);
    bodies_.push_back(b);
    return static_cast<int>(bodies_.size()) - 1;
  }
  std::string MeshAsset(const std::string& path, const Vector3d& scale,
                        const std::string& what);
  GeomSpec FrameGeom(const Frame& frame, const std::string& name,
                     PartLook kind);
  void AddRobot(const std::string& robot_name,
                const std::vector<Module>& modules,
                const std::vector<SensorModule>& sensor_modules,
                const std::vector<Frame>& loose_frames,
                const std::vector<Joint>& locks, bool servos,
                std::vector<MjcfLock>* lock_info);
  void AddSensorModuleParts(const std::string& robot_name, int index,
                            const SensorModule& sm, int body);
  void ConnectTree(const std::string& robot_name, std::vector<Node>& nodes,
                   const std::vector<Edge>& edges,
                   std::vector<MjcfLock>* lock_info);
  void AddSceneObjects();
  void AddTerrain();
  std::vector<int> WeldGroups() const;
  void MergeFlushFrames(const std::vector<int>& weld);
  void WriteBody(tinyxml2::XMLPrinter& out, int index) const;
  void WriteGeom(tinyxml2::XMLPrinter& out, const GeomSpec& g) const;
  // A file path as the MJCF names it: relative to MjcfOptions::file_dir
  // when given, else absolute.
  std::string WrittenPath(const std::string& absolute) const;

  const Scenario& s_;
  const MjcfOptions& options_;
  MjcfInfo* info_;
  std::vector<BodySpec> bodies_;
  std::vector<GeomSpec> world_geoms_;
  std::vector<ActuatorSpec> actuators_;
  std::vector<WeldSpec> welds_;
  std::vector<std::pair<std::string, std::string>> excludes_;
  std::vector<ElementSpec> assets_;
  std::vector<std::pair<std::string, std::string>> rangefinders_;  // name, site
  std::vector<ElementSpec> kind_sensors_;  // sensor kinds' MuJoCo sensors
  std::map<std::string, std::string> mesh_names_;  // key path|scale -> name
  std::string terrain_geom_type_;
};

std::string Builder::MeshAsset(const std::string& path, const Vector3d& scale,
                               const std::string& what) {
  if (IsEmbeddedMesh(path)) {
    EmbeddedMesh mesh;
    try {
      mesh = DecodeEmbeddedMesh(path);
    } catch (const std::exception& e) {
      throw std::runtime_error(what + ": " + e.what());
    }
    const uint64_t h = Fnv1a64(mesh.bytes.data(), mesh.bytes.size());
    std::string file = fmt::format("mrsim-mesh-{:016x}-{}", h, mesh.file_name);
    const std::string key = file + "|" + Vec(scale);
    auto it = mesh_names_.find(key);
    if (it != mesh_names_.end()) return it->second;
    if (options_.assets_in_memory) {
      if (info_) info_->memory_files.push_back({file, mesh.bytes});
    } else {
      const fs::path dir =
          !options_.asset_dir.empty()  ? fs::path(options_.asset_dir)
          : !options_.file_dir.empty() ? fs::path(options_.file_dir)
                                       : fs::temp_directory_path();
      const std::string out_path = fs::absolute(dir / file).string();
      std::ofstream out(out_path, std::ios::binary);
      out.write(reinterpret_cast<const char*>(mesh.bytes.data()),
                mesh.bytes.size());
      if (!out) {
        throw std::runtime_error(what + ": cannot write the mesh to '" +
                                 out_path + "'");
      }
      file = WrittenPath(out_path);
    }
    const std::string name = "mesh" + std::to_string(mesh_names_.size());
    mesh_names_[key] = name;
    assets_.push_back(
        {"mesh", {{"name", name}, {"file", file}, {"scale", Vec(scale)}}});
    return name;
  }
  fs::path p(path);
  if (p.is_relative() && !s_.base_dir.empty()) p = fs::path(s_.base_dir) / p;
  std::error_code ec;
  const std::string abs = fs::absolute(p, ec).lexically_normal().string();
  if (!fs::is_regular_file(abs, ec)) {
    throw std::runtime_error(what + ": cannot read mesh file '" + abs + "'");
  }
  const std::string key = abs + "|" + Vec(scale);
  auto it = mesh_names_.find(key);
  if (it != mesh_names_.end()) return it->second;
  const std::string name = "mesh" + std::to_string(mesh_names_.size());
  mesh_names_[key] = name;
  assets_.push_back(
      {"mesh",
       {{"name", name}, {"file", WrittenPath(abs)}, {"scale", Vec(scale)}}});
  return name;
}

GeomSpec Builder::FrameGeom(const Frame& frame, const std::string& name,
                            PartLook kind) {
  GeomSpec g;
  g.name = name;
  g.mass = frame.mass;
  g.material = frame.material_name;
  g.kind = kind;
  if (frame.is_mesh()) {
    g.type = "mesh";
    g.mesh = MeshAsset(frame.shape, frame.scale, "frame '" + frame.guid + "'");
  } else {
    g.type = "box";
    g.size = frame.scale / 2;
  }
  return g;
}

// What shows a kCentre sensor (the IMU, inside its module) in the viewer
// and the studio: a chip of the kind's colour on the module's top face
// with the module's axes as a small triad (x red, y green, z blue). Sites
// only: nothing of it collides or weighs.
void AddCentreMarker(const std::string& site, const SensorKind& kind,
                     const Vector3d& half, BodySpec* body) {
  const double c = std::clamp(0.35 * std::min(half.x(), half.y()), 0.004, 0.02);
  const double t = 0.25 * c;
  const Vector3d chip(0, 0, half.z() + t);
  auto rgba = [](const Vector3d& rgb) { return Vec(rgb) + " 1"; };
  SiteSpec look{site + "/look", chip};
  look.type = "box";
  look.size = Vector3d(c, c, t);
  look.rgba = rgba(kind.rgb);
  body->sites.push_back(look);
  const double length = 1.8 * c;
  const char* names[3] = {"/x", "/y", "/z"};
  for (int i = 0; i < 3; ++i) {
    const Vector3d axis = Vector3d::Unit(i);
    SiteSpec arm{site + names[i], chip + axis * (length / 2),
                 Quaterniond::FromTwoVectors(Vector3d::UnitZ(), axis)};
    arm.type = "capsule";
    arm.size = Vector3d(0.15 * c, length / 2, 0);
    arm.rgba = rgba(0.15 * Vector3d::Ones() + 0.8 * axis);
    body->sites.push_back(arm);
  }
}

// What shows a camera in the viewer and the studio: its frustum's four
// edges as thin capsules from the lens, as far as the module is small.
// Sites only, which a camera's own picture leaves out
// (CameraImageRenderer), so it never sees its own marker.
void AddFrustumMarker(const std::string& site, const SensorKind& kind,
                      const SensorCamera& c, const Vector3d& half,
                      BodySpec* body) {
  const double length = std::clamp(1.2 * half.minCoeff(), 0.01, 0.05);
  const double t = std::tan(c.camera.fovy * M_PI / 360);
  const double aspect =
      static_cast<double>(c.camera.width) / std::max(1, c.camera.height);
  const char* names[4] = {"/f0", "/f1", "/f2", "/f3"};
  for (int i = 0; i < 4; ++i) {
    // Corner directions in the camera frame (looking along -z).
    const Vector3d local((i & 1 ? 1 : -1) * t * aspect, (i & 2 ? 1 : -1) * t,
                         -1);
    const Vector3d dir = (c.rotation * local).normalized();
    SiteSpec edge{site + names[i], c.position + dir * (length / 2),
                  Quaterniond::FromTwoVectors(Vector3d::UnitZ(), dir)};
    edge.type = "capsule";
    edge.size = Vector3d(0.04 * length, length / 2, 0);
    edge.rgba = Vec(kind.rgb) + " 1";
    body->sites.push_back(edge);
  }
}

void Builder::AddSensorModuleParts(const std::string& robot_name, int index,
                                   const SensorModule& sm, int body) {
  // Every kind the same way by its mount (sensor_kind.h): a site per
  // instance (on a plate body of its own, on a face, or at the module's
  // centre), and the kind's MuJoCo sensors on that site.
  const Vector3d half = sm.size / 2;
  for (const SensorKind& kind : SensorKinds()) {
    for (int k = 0; k < kind.count(sm); ++k) {
      const std::string site =
          mjcf_names::SensorKindSite(robot_name, index, kind.name, k);
      switch (kind.mount) {
        case SensorMount::kCentre:
          bodies_[body].sites.push_back({site});
          AddCentreMarker(site, kind, half, &bodies_[body]);
          break;
        case SensorMount::kPlate: {
          const SensorPlate local = kind.plate(sm, k);
          const BodySpec& parent = bodies_[body];
          const int plate = AddBody(
              mjcf_names::SensorKindBody(robot_name, index, kind.name, k),
              parent.pos + parent.quat * local.position,
              parent.quat * local.rotation);
          bodies_[plate].parent = body;
          bodies_[body].children.push_back(plate);
          GeomSpec g;
          g.name = bodies_[plate].name;
          g.type = "box";
          g.size = local.size / 2;
          g.mass = local.mass;
          g.material = local.material;
          g.kind = kind.look;
          bodies_[plate].geoms.push_back(g);
          bodies_[plate].sites.push_back(
              {site, Vector3d::Zero(), Quaterniond::Identity()});
          break;
        }
        case SensorMount::kRay: {
          const SensorRay ray = kind.ray(sm, k);
          const Vector3d n = SensorFaceNormal(ray.face);
          const double h = std::abs(n.dot(half));
          // Site x axis = ray direction, at the face centre.
          bodies_[body].sites.push_back(
              {site, n * h,
               Quaterniond::FromTwoVectors(Vector3d::UnitX(), ray.direction)});
          if (options_.rangefinders) {
            // MuJoCo's own sensor for viewers and other tools: it looks
            // along its site's z axis and skips the sensor module's body,
            // not its plate, so Physics keeps its own ray casts.
            bodies_[body].sites.push_back(
                {site + "/range", n * h,
                 Quaterniond::FromTwoVectors(Vector3d::UnitZ(), ray.direction),
                 true});
            rangefinders_.push_back({site, site + "/range"});
          }
          if (ray.look_mass > 0 && ray.look_size.minCoeff() > 0) {
            // The sensor's own mass and look; it never collides (the
            // module does).
            GeomSpec g;
            g.name = site;
            g.type = "box";
            g.size = ray.look_size / 2;
            g.pos = n * (h + std::abs(n.dot(ray.look_size)) / 2);
            g.mass = ray.look_mass;
            g.material = sm.material_name;
            g.collide = false;
            g.kind = kind.look;
            bodies_[body].geoms.push_back(g);
          }
          break;
        }
        case SensorMount::kCamera: {
          const SensorCamera c = kind.camera(sm, k);
          bodies_[body].cameras.push_back(
              {site, c.position, c.rotation, c.camera.fovy});
          AddFrustumMarker(site, kind, c, half, &bodies_[body]);
          break;
        }
      }
      for (const SensorMujoco& ms : kind.mujoco) {
        kind_sensors_.push_back(
            {ms.element,
             {{"name", mjcf_names::SensorKindSensor(robot_name, index,
                                                    kind.name, k, ms.suffix)},
              {"site", site}}});
      }
    }
  }
}

void Builder::AddRobot(const std::string& robot_name,
                       const std::vector<Module>& modules,
                       const std::vector<SensorModule>& sensor_modules,
                       const std::vector<Frame>& loose_frames,
                       const std::vector<Joint>& locks, bool servos,
                       std::vector<MjcfLock>* lock_info) {
  std::vector<Node> nodes;
  std::vector<Edge> edges;
  std::map<std::string, int> by_guid;
  auto add_node = [&](const std::string& guid, const std::string& what,
                      int body, bool is_static) {
    if (!guid.empty()) by_guid[guid] = static_cast<int>(nodes.size());
    nodes.push_back({guid, what, body, is_static});
    return static_cast<int>(nodes.size()) - 1;
  };

  std::vector<std::array<int, 2>> module_nodes;
  for (size_t i = 0; i < modules.size(); ++i) {
    const Module& m = modules[i];
    std::array<int, 2> ids{};
    for (int f = 0; f < 2; ++f) {
      const Frame& frame = m.frames[f];
      const std::string name = mjcf_names::FrameBody(robot_name, i, f);
      const int body = AddBody(name, frame.position, frame.quat_rotation);
      GeomSpec g = FrameGeom(frame, name,
                             m.axis == Axis::kPitch ? PartLook::kPitchModule
                                                    : PartLook::kYawModule);
      // Passive wheels steer friction by each frame's own axes.
      g.mergeable = g.type == "box" && !m.passive_wheels && !frame.is_static;
      bodies_[body].geoms.push_back(g);
      ids[f] = add_node(frame.guid,
                        "robot '" + robot_name + "' module " +
                            std::to_string(i) + " frame " + std::to_string(f),
                        body, frame.is_static);
    }
    module_nodes.push_back(ids);
  }
  for (size_t i = 0; i < loose_frames.size(); ++i) {
    const Frame& frame = loose_frames[i];
    const std::string name = robot_name + "/f" + std::to_string(i);
    const int body = AddBody(name, frame.position, frame.quat_rotation);
    bodies_[body].geoms.push_back(
        FrameGeom(frame, name, PartLook::kLooseFrame));
    add_node(frame.guid, "loose frame " + std::to_string(i), body,
             frame.is_static);
  }
  std::vector<int> sm_nodes;
  for (size_t k = 0; k < sensor_modules.size(); ++k) {
    const SensorModule& sm = sensor_modules[k];
    const std::string name = mjcf_names::SensorModuleBody(robot_name, k);
    const int body = AddBody(name, sm.position, sm.quat_rotation);
    GeomSpec g;
    g.name = name;
    g.type = "box";
    g.size = sm.size / 2;
    g.mass = sm.mass;
    g.material = sm.material_name;
    g.kind = PartLook::kSensorModule;
    bodies_[body].geoms.push_back(g);
    AddSensorModuleParts(robot_name, static_cast<int>(k), sm, body);
    sm_nodes.push_back(add_node(
        sm.guid,
        "robot '" + robot_name + "' sensor module " + std::to_string(k), body,
        false));
  }

  // Hinges (or locked modules).
  for (size_t i = 0; i < modules.size(); ++i) {
    const Module& m = modules[i];
    Edge e;
    auto left = by_guid.find(m.joint.left_frame_guid);
    auto right = by_guid.find(m.joint.right_frame_guid);
    if (left != by_guid.end() && right != by_guid.end() &&
        left->second != right->second) {
      e.a = left->second;
      e.b = right->second;
    } else {
      e.a = module_nodes[i][0];
      e.b = module_nodes[i][1];
    }
    e.guid = m.joint.guid;
    e.hinge = m.joint.type == JointType::kHinge;
    const BodySpec& lb = bodies_[nodes[e.a].body];
    const Vector3d local_axis =
        m.axis == Axis::kPitch ? Vector3d::UnitY() : Vector3d::UnitZ();
    e.axis_world = lb.quat * local_axis;
    e.anchor_world = m.position;
    e.joint_name = mjcf_names::Hinge(robot_name, i);
    e.actuator_name = mjcf_names::Servo(robot_name, i);
    e.lower = m.joint.lower_range_limit;
    e.upper = m.joint.upper_range_limit;
    e.max_vel = m.joint.max_vel;
    e.kv = m.joint.velocity_gain;
    e.max_torque = m.joint.max_torque;
    e.servo = servos;
    edges.push_back(e);
  }
  // Locks between parts; a loose hinge joint becomes a hinge, passive
  // unless it asks for a servo (Joint::servo), then driven as a module's.
  std::map<std::string, int> guid_uses;
  for (const Joint& j : locks) ++guid_uses[j.guid];
  for (size_t k = 0; k < locks.size(); ++k) {
    const Joint& j = locks[k];
    auto left = by_guid.find(j.left_frame_guid);
    auto right = by_guid.find(j.right_frame_guid);
    if (left == by_guid.end() || right == by_guid.end()) {
      throw std::logic_error("joint '" + j.guid + "' was not validated");
    }
    Edge e;
    e.a = left->second;
    e.b = right->second;
    e.guid = j.guid;
    e.hinge = j.type == JointType::kHinge;
    if (!e.hinge) {
      // Placeholder guids (empty, or the all-zero guid on every lock) do
      // not name a lock; the lock's place does.
      e.lock = !j.guid.empty() && guid_uses[j.guid] == 1
                   ? j.guid
                   : "lock" + std::to_string(k);
      e.weld = j.break_force > 0;
      lock_info->push_back({e.lock, "", j.break_force});
    }
    if (e.hinge) {
      const BodySpec& lb = bodies_[nodes[e.a].body];
      const BodySpec& rb = bodies_[nodes[e.b].body];
      e.axis_world = lb.quat * Vector3d::UnitY();
      e.anchor_world = (lb.pos + rb.pos) / 2;
      e.joint_name = robot_name + "/j" + std::to_string(k) + "/hinge";
      e.lower = j.lower_range_limit;
      e.upper = j.upper_range_limit;
      if (j.servo) {
        e.actuator_name = robot_name + "/j" + std::to_string(k) + "/servo";
        e.max_vel = j.max_vel;
        e.kv = j.velocity_gain;
        e.max_torque = j.max_torque;
        e.servo = true;
      }
    }
    edges.push_back(e);
  }
  // A sensor module no lock mentions is locked to the nearest frames of its
  // neighbouring modules (leftMod_Nr / rightMod_Nr).
  for (size_t k = 0; k < sensor_modules.size(); ++k) {
    const int node = sm_nodes[k];
    bool connected = false;
    for (const Edge& e : edges) connected |= e.a == node || e.b == node;
    if (connected) continue;
    for (int side = 0; side < 2; ++side) {
      const int nr = side == 0 ? sensor_modules[k].left_mod_nr
                               : sensor_modules[k].right_mod_nr;
      if (nr < 0) continue;
      for (size_t i = 0; i < modules.size(); ++i) {
        if (modules[i].mod_nr != nr) continue;
        const Vector3d p = bodies_[nodes[node].body].pos;
        int best = module_nodes[i][0];
        if ((bodies_[nodes[module_nodes[i][1]].body].pos - p).norm() <
            (bodies_[nodes[best].body].pos - p).norm()) {
          best = module_nodes[i][1];
        }
        Edge e;
        e.a = best;
        e.b = node;
        e.guid = sensor_modules[k].guid + " (implicit lock)";
        e.lock = "sm" + std::to_string(k) + "/lock" + std::to_string(side);
        lock_info->push_back({e.lock, "", 0.0});
        edges.push_back(e);
        break;
      }
    }
  }
  for (Edge& e : edges) {
    if (!e.lock.empty() && options_.weld_locks.count(robot_name + "/" + e.lock))
      e.weld = true;
  }
  ConnectTree(robot_name, nodes, edges, lock_info);
}

void Builder::ConnectTree(const std::string& robot_name,
                          std::vector<Node>& nodes,
                          const std::vector<Edge>& edges,
                          std::vector<MjcfLock>* lock_info) {
  // Spanning forest: every hinge must be a tree edge (MuJoCo joints live in
  // the tree), locks join what the hinges left apart; any other lock
  // closes a loop and becomes a weld equality, as do locks that may be
  // released (weld) and locks that would nest bodies too deep.
  auto add_weld = [&](const Edge& e) {
    const std::string name = mjcf_names::Weld(robot_name, e.lock);
    welds_.push_back(
        {name, bodies_[nodes[e.a].body].name, bodies_[nodes[e.b].body].name});
    for (MjcfLock& l : *lock_info) {
      if (l.name == e.lock) l.weld = name;
    }
  };
  std::vector<int> uf(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) uf[n] = static_cast<int>(n);
  std::function<int(int)> find = [&](int n) {
    return uf[n] == n ? n : uf[n] = find(uf[n]);
  };
  std::vector<bool> in_tree(edges.size(), false);
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t ei = 0; ei < edges.size(); ++ei) {
      const Edge& e = edges[ei];
      if (e.hinge != (pass == 0)) continue;
      const int ra = find(e.a), rb = find(e.b);
      if (ra == rb || e.weld) {
        if (e.hinge) {
          throw std::logic_error("hinge '" + e.guid + "' was not validated");
        }
        add_weld(e);
        continue;
      }
      uf[ra] = rb;
      in_tree[ei] = true;
    }
  }
  // Connected parts never collide with each other (MuJoCo filters only
  // parent and child, and not at all when the parent is the world).
  for (const Edge& e : edges) {
    if (e.a != e.b) {
      excludes_.push_back(
          {bodies_[nodes[e.a].body].name, bodies_[nodes[e.b].body].name});
    }
  }
  std::vector<std::vector<int>> incident(nodes.size());
  for (size_t ei = 0; ei < edges.size(); ++ei) {
    if (!in_tree[ei]) continue;
    incident[edges[ei].a].push_back(static_cast<int>(ei));
    incident[edges[ei].b].push_back(static_cast<int>(ei));
  }
  std::vector<bool> visited(nodes.size(), false);
  std::vector<int> depth(nodes.size(), 0);
  // Static parts first so their component hangs from the world.
  std::vector<int> order;
  for (size_t n = 0; n < nodes.size(); ++n)
    if (nodes[n].is_static) order.push_back(n);
  for (size_t n = 0; n < nodes.size(); ++n)
    if (!nodes[n].is_static) order.push_back(n);
  int component = 0;
  for (int root : order) {
    if (visited[root]) continue;
    auto make_root = [&](int node) {
      BodySpec& rb = bodies_[nodes[node].body];
      if (!nodes[node].is_static) {
        rb.joint = JointKind::kFree;
        rb.joint_name = mjcf_names::RootJoint(robot_name, component);
      }
      ++component;
    };
    make_root(root);
    visited[root] = true;
    std::queue<int> queue;
    queue.push(root);
    while (!queue.empty()) {
      const int n = queue.front();
      queue.pop();
      for (int ei : incident[n]) {
        const Edge& e = edges[ei];
        const int other = e.a == n ? e.b : e.a;
        if (visited[other]) continue;
        visited[other] = true;
        depth[other] = depth[n] + 1;
        if (depth[other] > kMaxBodyDepth && !e.hinge) {
          // Too deep for XML: a new sub-tree, welded where the lock is.
          depth[other] = 0;
          add_weld(e);
          make_root(other);
          queue.push(other);
          continue;
        }
        const int pb = nodes[n].body, cb = nodes[other].body;
        bodies_[cb].parent = pb;
        bodies_[pb].children.push_back(cb);
        if (nodes[other].is_static) {
          // A static part inside a moving tree stays where it is.
          welds_.push_back(
              {bodies_[cb].name + "/static", bodies_[cb].name, ""});
        }
        if (e.hinge) {
          BodySpec& c = bodies_[cb];
          c.joint = JointKind::kHinge;
          c.joint_name = e.joint_name;
          // Positive angle: b turns about +axis relative to a.
          const double sign = other == e.b ? 1.0 : -1.0;
          c.axis = c.quat.conjugate() * (sign * e.axis_world);
          c.anchor = c.quat.conjugate() * (e.anchor_world - c.pos);
          c.lower = e.lower;
          c.upper = e.upper;
        }
        queue.push(other);
      }
    }
  }
  // Servos in chain order.
  for (size_t ei = 0; ei < edges.size(); ++ei) {
    const Edge& e = edges[ei];
    if (in_tree[ei] && e.hinge && e.servo) {
      actuators_.push_back(
          {e.actuator_name, e.joint_name, e.max_vel, e.kv, e.max_torque});
    }
  }
}

void Builder::AddSceneObjects() {
  for (size_t i = 0; i < s_.scene_objects.size(); ++i) {
    if (i < options_.skip_scene_objects.size() &&
        options_.skip_scene_objects[i]) {
      continue;
    }
    const SceneObject& o = s_.scene_objects[i];
    const std::string name = mjcf_names::SceneObject(i);
    GeomSpec g;
    g.name = name;
    g.material = o.material_name;
    g.mass = o.mass;
    switch (o.shape) {
      case PrimitiveShape::kBox:
        g.type = "box";
        g.size = o.size / 2;
        break;
      case PrimitiveShape::kSphere:
        g.type = "sphere";
        g.size = Vector3d(o.size.x() / 2, 0, 0);
        break;
      case PrimitiveShape::kCylinder:
        g.type = "cylinder";
        g.size = Vector3d(o.size.x() / 2, o.size.z() / 2, 0);
        break;
      case PrimitiveShape::kCapsule: {
        // size.z is the total length, caps included.
        const double r = o.size.x() / 2;
        g.type = "capsule";
        g.size = Vector3d(r, std::max(o.size.z() / 2 - r, 1e-6), 0);
        break;
      }
    }
    const int body = AddBody(name, o.position, o.quat_rotation);
    if (!o.is_static) {
      bodies_[body].joint = JointKind::kFree;
      bodies_[body].joint_name = name;
    } else if (!(g.mass > 0)) {
      g.mass = 1.0;  // irrelevant for a body welded to the world
    }
    bodies_[body].geoms.push_back(g);
    // Its cameras, on the faces of the box around it, as a sensor
    // module's: on a static object, a fixed view of the world.
    const SensorKind* camera_kind = FindSensorKind("camera");
    const Vector3d box = SceneObjectBox(o);
    for (size_t k = 0; k < o.cameras.size(); ++k) {
      SensorCamera c;
      c.camera = o.cameras[k];
      c.face = c.camera.sensor_position;
      const CameraPose pose = CameraOnFace(c.camera, box);
      c.position = pose.position;
      c.rotation = pose.rotation;
      const std::string camera_name = mjcf_names::SceneObjectCamera(
          static_cast<int>(i), static_cast<int>(k));
      bodies_[body].cameras.push_back(
          {camera_name, c.position, c.rotation, c.camera.fovy});
      AddFrustumMarker(camera_name, *camera_kind, c, box / 2, &bodies_[body]);
    }
  }
}

void Builder::AddTerrain() {
  const Scene& scene = s_.scene;
  GeomSpec g;
  g.name = mjcf_names::Terrain();
  g.material = scene.material_name;
  if (scene.height_image.empty()) {
    g.type = "plane";
    g.size = Vector3d(0, 0, 0.05);
    g.pos = scene.position;
    world_geoms_.push_back(g);
    return;
  }
  const TerrainImage image = LoadTerrainImage(scene, s_.base_dir);
  const double rx = image.cols * scene.meters_per_pixel / 2;
  const double ry = image.rows * scene.meters_per_pixel / 2;
  // MuJoCo needs a positive elevation range; a flat image still gets one.
  const double top = std::max(scene.height, 1e-6);
  const double bottom = std::max(0.05, 0.1 * top);
  ElementSpec hfield{
      "hfield",
      {{"name", "terrain"},
       {"size", Num(rx) + " " + Num(ry) + " " + Num(top) + " " + Num(bottom)}}};
  if (options_.hfield_data_after_compile) {
    hfield.attrs.push_back({"nrow", std::to_string(image.rows)});
    hfield.attrs.push_back({"ncol", std::to_string(image.cols)});
  } else {
    std::string path;
    const bool png_file = TerrainImageIsFile(scene, s_.base_dir, &path) &&
                          fs::path(path).extension() == ".png";
    if (!png_file) {
      // Write the decoded image as an 8-bit grey PNG MuJoCo can read.
      std::vector<unsigned char> grey(image.grey.size());
      for (size_t i = 0; i < grey.size(); ++i) {
        grey[i] = static_cast<unsigned char>(
            std::lround(std::clamp(image.grey[i], 0.0f, 1.0f) * 255.0f));
      }
      std::vector<unsigned char> png;
      stbi_write_png_to_func(
          [](void* out, void* data, int size) {
            auto* bytes = static_cast<unsigned char*>(data);
            static_cast<std::vector<unsigned char>*>(out)->insert(
                static_cast<std::vector<unsigned char>*>(out)->end(), bytes,
                bytes + size);
          },
          &png, image.cols, image.rows, 1, grey.data(), image.cols);
      const uint64_t h = Fnv1a64(png.data(), png.size());
      const fs::path dir =
          !options_.asset_dir.empty()  ? fs::path(options_.asset_dir)
          : !options_.file_dir.empty() ? fs::path(options_.file_dir)
                                       : fs::temp_directory_path();
      path = fs::absolute(dir / fmt::format("mrsim-terrain-{:016x}.png", h))
                 .string();
      std::ofstream out(path, std::ios::binary);
      out.write(reinterpret_cast<const char*>(png.data()), png.size());
      if (!out) {
        throw std::runtime_error("cannot write the terrain image to '" + path +
                                 "'");
      }
    }
    hfield.attrs.push_back({"file", WrittenPath(path)});
  }
  assets_.push_back(hfield);
  g.type = "hfield";
  g.pos = scene.position + Vector3d(rx, ry, 0);
  world_geoms_.push_back(g);
}

// Weld group of each body as MuJoCo computes body_weldid: the nearest
// ancestor (or itself) with a joint; -1 for bodies welded to the world.
std::vector<int> Builder::WeldGroups() const {
  std::vector<int> group(bodies_.size(), -1);
  std::function<int(int)> find = [&](int b) -> int {
    if (b < 0) return -1;
    if (bodies_[b].joint != JointKind::kNone) return b;
    return find(bodies_[b].parent);
  };
  for (size_t b = 0; b < bodies_.size(); ++b) group[b] = find(b);
  return group;
}

// A locked pair of module frames lying flush is one rigid box as far as the
// ground can tell; as two boxes it touched down at eight corners, four of
// them doubled where the frames meet, which only added constraint rows
// (memory grows with their square, solver time faster than linearly). The
// frames stay as they are for looks, mass and sensors; one hidden box of
// their union collides for both. Only frames of one weld group (no joint,
// no weld between them) merge, so the bodies move exactly as before.
void Builder::MergeFlushFrames(const std::vector<int>& weld) {
  struct Piece {
    OrientedBox box;
    int body;                                  // where the union's geom goes
    std::vector<std::pair<int, int>> sources;  // (body, geom index)
  };
  std::map<int, std::vector<Piece>> groups;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (weld[b] < 0) continue;
    for (size_t gi = 0; gi < bodies_[b].geoms.size(); ++gi) {
      const GeomSpec& g = bodies_[b].geoms[gi];
      if (!g.mergeable || !g.collide) continue;
      const BodySpec& body = bodies_[b];
      Piece p;
      p.box.center = body.pos + body.quat * g.pos;
      p.box.quat = Normalized(body.quat * g.quat);
      p.box.half = g.size;
      p.body = static_cast<int>(b);
      p.sources.push_back({static_cast<int>(b), static_cast<int>(gi)});
      groups[weld[b]].push_back(std::move(p));
    }
  }
  std::set<std::pair<std::string, std::string>> excluded(excludes_.begin(),
                                                         excludes_.end());
  const auto geom = [this](const std::pair<int, int>& s) -> GeomSpec& {
    return bodies_[s.first].geoms[s.second];
  };
  for (auto& [group, pieces] : groups) {
    // One pass, quadratic in the group at most (a design may lock many
    // frames into one body): frames come in chain order, so a row of flush
    // boxes grows from its first one.
    for (size_t i = 0; i < pieces.size(); ++i) {
      for (size_t j = i + 1; j < pieces.size();) {
        const auto u = geom(pieces[i].sources[0]).material ==
                               geom(pieces[j].sources[0]).material
                           ? FlushBoxUnion(pieces[i].box, pieces[j].box)
                           : std::nullopt;
        if (!u) {
          ++j;
          continue;
        }
        pieces[i].box = *u;
        pieces[i].sources.insert(pieces[i].sources.end(),
                                 pieces[j].sources.begin(),
                                 pieces[j].sources.end());
        pieces.erase(pieces.begin() + j);
      }
    }
    for (const Piece& p : pieces) {
      if (p.sources.size() < 2) continue;
      const GeomSpec& first = geom(p.sources[0]);
      BodySpec& body = bodies_[p.body];
      GeomSpec u;
      u.name = first.name + "/contact";
      u.type = "box";
      u.size = p.box.half;
      u.pos = body.quat.conjugate() * (p.box.center - body.pos);
      u.quat = Normalized(body.quat.conjugate() * p.box.quat);
      u.material = first.material;
      u.kind = first.kind;
      u.contact_only = true;
      for (const auto& s : p.sources) geom(s).collide = false;
      body.geoms.push_back(u);
      // Whatever must never touch a source's body (a lock that closes a
      // loop joins bodies of other weld groups) must not touch the box.
      std::set<std::string> from;
      for (const auto& s : p.sources) from.insert(bodies_[s.first].name);
      for (size_t e = 0, n = excludes_.size(); e < n; ++e) {
        const auto [x, y] = excludes_[e];
        if (from.count(x) && from.count(y)) continue;
        std::pair<std::string, std::string> add;
        if (from.count(x) && x != body.name) {
          add = {body.name, y};
        } else if (from.count(y) && y != body.name) {
          add = {x, body.name};
        } else {
          continue;
        }
        if (!excluded.count(add) && !excluded.count({add.second, add.first})) {
          excluded.insert(add);
          excludes_.push_back(add);
        }
      }
    }
  }
}

std::string Builder::WrittenPath(const std::string& absolute) const {
  if (options_.file_dir.empty()) return absolute;
  const fs::path dir = fs::absolute(options_.file_dir).lexically_normal();
  return fs::path(absolute).lexically_relative(dir).string();
}

void Builder::WriteGeom(tinyxml2::XMLPrinter& out, const GeomSpec& g) const {
  out.OpenElement("geom");
  out.PushAttribute("name", g.name.c_str());
  out.PushAttribute("type", g.type.c_str());
  if (g.type == "mesh") {
    out.PushAttribute("mesh", g.mesh.c_str());
  } else if (g.type == "hfield") {
    out.PushAttribute("hfield", "terrain");
  } else {
    out.PushAttribute("size", Vec(g.size).c_str());
  }
  if (!g.pos.isZero()) out.PushAttribute("pos", Vec(g.pos).c_str());
  if (!g.quat.isApprox(Quaterniond::Identity(), 0)) {
    out.PushAttribute("quat", Quat(g.quat).c_str());
  }
  if (g.mass > 0) out.PushAttribute("mass", Num(g.mass).c_str());
  const bool ground = g.type == "plane" || g.type == "hfield";
  out.PushAttribute("material", ground ? "scene/ground"
                                       : LookName(g.kind, g.material).c_str());
  if (g.contact_only) {
    out.PushAttribute("density", "0");
    out.PushAttribute("group", std::to_string(kMjcfContactGroup).c_str());
  }
  if (!g.collide) {
    out.PushAttribute("contype", "0");
    out.PushAttribute("conaffinity", "0");
    out.PushAttribute("group", "1");
  } else {
    for (const auto& [k, v] : ContactGeomAttributes(s_, g.material)) {
      out.PushAttribute(k.c_str(), v.c_str());
    }
  }
  out.CloseElement();
}

void Builder::WriteBody(tinyxml2::XMLPrinter& out, int index) const {
  const BodySpec& b = bodies_[index];
  Vector3d pos = b.pos;
  Quaterniond quat = b.quat;
  if (b.parent >= 0) {
    const BodySpec& p = bodies_[b.parent];
    pos = p.quat.conjugate() * (b.pos - p.pos);
    quat = Normalized(p.quat.conjugate() * b.quat);
  }
  out.OpenElement("body");
  out.PushAttribute("name", b.name.c_str());
  out.PushAttribute("pos", Vec(pos).c_str());
  out.PushAttribute("quat", Quat(quat).c_str());
  if (b.joint == JointKind::kFree) {
    out.OpenElement("freejoint");
    out.PushAttribute("name", b.joint_name.c_str());
    out.CloseElement();
  } else if (b.joint == JointKind::kHinge) {
    // MuJoCo needs lower < upper; equal limits still pin the joint.
    const double lower = b.lower < b.upper ? b.lower : b.lower - 1e-9;
    const double upper = b.lower < b.upper ? b.upper : b.upper + 1e-9;
    out.OpenElement("joint");
    out.PushAttribute("name", b.joint_name.c_str());
    out.PushAttribute("type", "hinge");
    out.PushAttribute("pos", Vec(b.anchor).c_str());
    out.PushAttribute("axis", Vec(b.axis).c_str());
    out.PushAttribute("limited", "true");
    out.PushAttribute("range", (Num(lower) + " " + Num(upper)).c_str());
    out.PushAttribute("armature", Num(ServoModel::kArmature).c_str());
    out.CloseElement();
  }
  for (const GeomSpec& g : b.geoms) WriteGeom(out, g);
  for (const SiteSpec& site : b.sites) {
    out.OpenElement("site");
    out.PushAttribute("name", site.name.c_str());
    out.PushAttribute("pos", Vec(site.pos).c_str());
    out.PushAttribute("quat", Quat(site.quat).c_str());
    if (site.type.empty()) {
      out.PushAttribute("size", "0.004");
    } else {
      out.PushAttribute("type", site.type.c_str());
      out.PushAttribute("size", Vec(site.size).c_str());
      out.PushAttribute("rgba", site.rgba.c_str());
    }
    if (site.rangefinder) out.PushAttribute("group", "4");
    out.CloseElement();
  }
  for (const CameraSpec& c : b.cameras) {
    out.OpenElement("camera");
    out.PushAttribute("name", c.name.c_str());
    out.PushAttribute("pos", Vec(c.pos).c_str());
    out.PushAttribute("quat", Quat(c.quat).c_str());
    out.PushAttribute("fovy", Num(c.fovy).c_str());
    out.CloseElement();
  }
  for (int c : b.children) WriteBody(out, c);
  out.CloseElement();
}

std::string Builder::Build() {
  ValidateScenario(s_);
  for (size_t r = 0; r < s_.robots.size(); ++r) {
    const Robot& robot = s_.robots[r];
    const std::string name = mjcf_names::RobotName(s_, r);
    std::vector<MjcfLock> locks;
    AddRobot(name, robot.modules, robot.sensor_modules, {}, robot.locks, true,
             &locks);
    if (info_) info_->robot_locks.push_back(std::move(locks));
  }
  if (!s_.loose_frames.empty() || !s_.loose_sensor_modules.empty()) {
    std::vector<MjcfLock> locks;
    AddRobot(mjcf_names::LooseRobot(), {}, s_.loose_sensor_modules,
             s_.loose_frames, s_.loose_joints, false, &locks);
    if (info_) info_->loose_locks = std::move(locks);
  }
  AddSceneObjects();
  AddTerrain();

  const std::vector<int> weld = WeldGroups();
  MergeFlushFrames(weld);
  int ncollide = 0, nhinge = 0, nfree = 0;
  for (const BodySpec& b : bodies_) {
    for (const GeomSpec& g : b.geoms) ncollide += g.collide;
    nhinge += b.joint == JointKind::kHinge;
    nfree += b.joint == JointKind::kFree;
  }

  // Pairs for material pairs of two different materials, with the same
  // filters MuJoCo applies to contacts it finds on its own.
  struct CollGeom {
    std::string name, material, body;
    int group;
  };
  std::vector<CollGeom> coll;
  for (const GeomSpec& g : world_geoms_) {
    coll.push_back({g.name, g.material, "", -1});
  }
  for (size_t b = 0; b < bodies_.size(); ++b) {
    for (const GeomSpec& g : bodies_[b].geoms) {
      if (g.collide) {
        coll.push_back({g.name, g.material, bodies_[b].name, weld[b]});
      }
    }
  }
  auto parent_group = [&](int group) {
    if (group < 0) return -1;
    const int p = bodies_[group].parent;
    return p < 0 ? -1 : weld[p];
  };
  std::set<std::pair<std::string, std::string>> excluded;
  for (const auto& e : excludes_) {
    excluded.insert(e);
    excluded.insert({e.second, e.first});
  }
  struct PairSpec {
    std::string geom1, geom2;
    const ContactFriction* entry;
  };
  std::vector<PairSpec> pairs;
  for (size_t i = 0; i < coll.size(); ++i) {
    for (size_t j = i + 1; j < coll.size(); ++j) {
      const CollGeom& a = coll[i];
      const CollGeom& b = coll[j];
      if (a.material == b.material) continue;
      if (a.group == b.group || excluded.count({a.body, b.body})) continue;
      if (a.group >= 0 && b.group >= 0 &&
          (parent_group(a.group) == b.group ||
           parent_group(b.group) == a.group)) {
        continue;
      }
      const ContactFriction* cf =
          FindContactFriction(s_, a.material, b.material);
      if (cf) pairs.push_back({a.name, b.name, cf});
    }
  }

  tinyxml2::XMLPrinter out;
  auto attr = [&out](const char* name, const std::string& value) {
    out.PushAttribute(name, value.c_str());
  };
  auto element = [&](const ElementSpec& e) {
    out.OpenElement(e.tag.c_str());
    for (const auto& [k, v] : e.attrs) attr(k.c_str(), v);
    out.CloseElement();
  };
  out.OpenElement("mujoco");
  attr("model", "mrsim");
  element({"compiler", {{"angle", "radian"}, {"inertiafromgeom", "true"}}});
  element({"option",
           {{"timestep", Num(s_.settings.timestep)},
            {"gravity", Vec(s_.settings.gravity)},
            {"integrator", "Euler"}}});
  const MjcfSizes sizes = MjcfSizesFor(
      ncollide, static_cast<int>(welds_.size()), nhinge, nhinge + 6 * nfree);
  element({"size",
           {{"nconmax", std::to_string(sizes.nconmax)},
            {"njmax", std::to_string(sizes.njmax)}}});
  // MuJoCo's usual look (its model gallery): headlight, haze, a gradient
  // sky and a checker floor.
  out.OpenElement("visual");
  element({"headlight",
           {{"ambient", "0.4 0.4 0.4"},
            {"diffuse", "0.6 0.6 0.6"},
            {"specular", "0.1 0.1 0.1"}}});
  element({"rgba", {{"haze", "0.15 0.25 0.35 1"}}});
  element({"global", {{"azimuth", "120"}, {"elevation", "-20"}}});
  out.CloseElement();

  out.OpenElement("asset");
  if (options_.textures) {
    element({"texture",
             {{"name", "scene/sky"},
              {"type", "skybox"},
              {"builtin", "gradient"},
              {"rgb1", "0.3 0.5 0.7"},
              {"rgb2", "0 0 0"},
              {"width", "512"},
              {"height", "3072"}}});
    element({"texture",
             {{"name", "scene/checker"},
              {"type", "2d"},
              {"builtin", "checker"},
              {"rgb1", "0.1 0.2 0.3"},
              {"rgb2", "0.2 0.3 0.4"},
              {"mark", "edge"},
              {"markrgb", "0.8 0.8 0.8"},
              {"width", "300"},
              {"height", "300"}}});
    element({"material",
             {{"name", "scene/ground"},
              {"texture", "scene/checker"},
              {"texuniform", "true"},
              {"texrepeat", "4 4"},
              {"reflectance", "0.2"}}});
  } else {
    element({"material", {{"name", "scene/ground"}}});
  }
  std::set<std::string> looks;
  auto add_look = [&](const GeomSpec& g) {
    const std::string name = LookName(g.kind, g.material);
    if (!looks.insert(name).second) return;
    const Vector3d rgb = LookRgb(g.kind, g.material);
    element({"material",
             {{"name", name},
              {"rgba", fmt::format("{:.3f} {:.3f} {:.3f} 1", rgb.x(), rgb.y(),
                                   rgb.z())},
              {"specular", "0.3"},
              {"shininess", "0.3"}}});
  };
  for (const BodySpec& b : bodies_) {
    for (const GeomSpec& g : b.geoms) add_look(g);
  }
  for (const ElementSpec& a : assets_) element(a);
  out.CloseElement();

  out.OpenElement("worldbody");
  element({"light",
           {{"name", "sun"},
            {"directional", "true"},
            {"pos", "0 0 5"},
            {"dir", "0 0 -1"},
            {"diffuse", "0.5 0.5 0.5"}}});
  for (const GeomSpec& g : world_geoms_) {
    out.OpenElement("geom");
    attr("name", g.name);
    attr("type", g.type);
    if (g.type == "hfield") {
      attr("hfield", "terrain");
    } else {
      attr("size", Vec(g.size));
    }
    attr("pos", Vec(g.pos));
    attr("material", "scene/ground");
    for (const auto& [k, v] : ContactGeomAttributes(s_, g.material)) {
      attr(k.c_str(), v);
    }
    out.CloseElement();
  }
  // Fluid regions as translucent boxes for viewers; sites, so rays and
  // contacts ignore them (their forces are applied by Physics).
  for (size_t i = 0; i < s_.fluid_regions.size(); ++i) {
    const FluidRegion& f = s_.fluid_regions[i];
    element({"site",
             {{"name", "scene/fluid" + std::to_string(i)},
              {"type", "box"},
              {"pos", Vec(f.position)},
              {"size", Vec(f.size / 2)},
              {"rgba", f.kind == FluidKind::kWater ? "0.2 0.4 0.9 0.25"
                                                   : "0.9 0.9 0.9 0.08"}}});
  }
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].parent < 0) WriteBody(out, b);
  }
  out.CloseElement();

  if (!pairs.empty() || !excludes_.empty()) {
    out.OpenElement("contact");
    for (const auto& e : excludes_) {
      element({"exclude", {{"body1", e.first}, {"body2", e.second}}});
    }
    for (const PairSpec& p : pairs) {
      ElementSpec e{"pair", {{"geom1", p.geom1}, {"geom2", p.geom2}}};
      for (const auto& kv : ContactPairAttributes(*p.entry)) {
        e.attrs.push_back(kv);
      }
      element(e);
    }
    out.CloseElement();
  }
  if (!welds_.empty()) {
    out.OpenElement("equality");
    for (const WeldSpec& w : welds_) {
      ElementSpec e{"weld", {{"name", w.name}, {"body1", w.body1}}};
      if (!w.body2.empty()) e.attrs.push_back({"body2", w.body2});
      // As stiff as the timestep allows: a lock is meant to be rigid.
      e.attrs.push_back({"solref", Num(2 * s_.settings.timestep) + " 1"});
      element(e);
    }
    out.CloseElement();
  }
  if (!actuators_.empty()) {
    out.OpenElement("actuator");
    for (const ActuatorSpec& a : actuators_) {
      const double v = std::abs(a.max_vel);
      ElementSpec e{"velocity",
                    {{"name", a.name}, {"joint", a.joint}, {"kv", Num(a.kv)}}};
      // Physics clamps the command itself; MuJoCo rejects an empty range.
      if (v > 0) {
        e.attrs.push_back({"ctrllimited", "true"});
        e.attrs.push_back({"ctrlrange", Num(-v) + " " + Num(v)});
      }
      e.attrs.push_back({"forcelimited", "true"});
      e.attrs.push_back(
          {"forcerange", Num(-a.max_torque) + " " + Num(a.max_torque)});
      element(e);
    }
    out.CloseElement();
  }
  if (!rangefinders_.empty() || !kind_sensors_.empty()) {
    out.OpenElement("sensor");
    for (const auto& r : rangefinders_) {
      element({"rangefinder", {{"name", r.first}, {"site", r.second}}});
    }
    for (const ElementSpec& e : kind_sensors_) element(e);
    out.CloseElement();
  }
  out.CloseElement();
  return out.CStr();
}

}  // namespace

std::string BuildMjcf(const Scenario& scenario) {
  return BuildMjcf(scenario, MjcfOptions{});
}

int MjcfMaxRows(int nv) {
  // Largest j with 12 j^2 + 24 j nv <= 1.9e9 (room for the rest of mjData).
  const double budget = 1.9e9 / 12;
  return static_cast<int>(-double(nv) + std::sqrt(double(nv) * nv + budget));
}

MjcfSizes MjcfSizesFor(int colliding_geoms, int welds, int hinges, int nv) {
  // What the model needs at rest: every colliding box flat on the ground
  // (4 corner contacts of 4 pyramidal rows each), every weld (6 rows) and
  // every hinge at its limit (1 row). Small models keep room for piles and
  // self-contact (up to 200 contacts more); long chains get their resting
  // need, since memory grows with its square. More than that (a pile, a
  // coiled chain) grows the buffers at run time (Physics), so nothing is
  // ever dropped.
  MjcfSizes sizes;
  sizes.nconmax =
      std::max(kMjcfMinContacts,
               4 * colliding_geoms + std::max(0, 200 - colliding_geoms));
  const long rows = static_cast<long>(kMjcfRowsPerContact) * sizes.nconmax +
                    6L * welds + hinges;
  sizes.njmax = static_cast<int>(std::min<long>(rows, MjcfMaxRows(nv)));
  return sizes;
}

std::string BuildMjcf(const Scenario& scenario, const MjcfOptions& options) {
  return Builder(scenario, options, nullptr).Build();
}

std::string BuildMjcf(const Scenario& scenario, const MjcfOptions& options,
                      MjcfInfo* info) {
  if (info) {
    info->robot_locks.clear();
    info->loose_locks.clear();
    info->memory_files.clear();
  }
  return Builder(scenario, options, info).Build();
}

}  // namespace mrsim

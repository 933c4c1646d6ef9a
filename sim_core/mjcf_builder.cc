#include "sim_core/mjcf_builder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <queue>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sim_core/contact_model.h"
#include "sim_core/scenario_validate.h"
#include "sim_core/terrain.h"

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
std::string Esc(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// A stable colour per material so parts look apart in the viewer.
std::string Rgba(const std::string& material) {
  static const char* kPalette[] = {"0.85 0.45 0.2 1", "0.3 0.55 0.85 1",
                                   "0.4 0.75 0.35 1", "0.8 0.75 0.3 1",
                                   "0.65 0.4 0.75 1", "0.5 0.5 0.5 1"};
  size_t h = 0;
  for (char c : material) h = h * 31 + static_cast<unsigned char>(c);
  return kPalette[h % (sizeof(kPalette) / sizeof(kPalette[0]))];
}

Quaterniond Normalized(const Quaterniond& q) {
  const double n = q.norm();
  if (!(n > 0) || !std::isfinite(n)) return Quaterniond::Identity();
  return Quaterniond(q.coeffs() / n);
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
};

struct SiteSpec {
  std::string name;
  Vector3d pos = Vector3d::Zero();
  Quaterniond quat = Quaterniond::Identity();
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
};

struct ActuatorSpec {
  std::string name, joint;
  double max_vel = 0;
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
  double lower = 0, upper = 0, max_vel = 0;
  bool servo = false;
};

class Builder {
 public:
  Builder(const Scenario& scenario, const MjcfOptions& options)
      : s_(scenario), options_(options) {}

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
  GeomSpec FrameGeom(const Frame& frame, const std::string& name);
  void AddRobot(const std::string& robot_name,
                const std::vector<Module>& modules,
                const std::vector<SensorModule>& sensor_modules,
                const std::vector<Frame>& loose_frames,
                const std::vector<Joint>& locks, bool servos);
  void AddSensorModuleParts(const std::string& robot_name, int index,
                            const SensorModule& sm, int body);
  void ConnectTree(const std::string& robot_name, std::vector<Node>& nodes,
                   const std::vector<Edge>& edges);
  void AddSceneObjects();
  void AddTerrain();
  std::vector<int> WeldGroups() const;
  void WriteBody(std::ostringstream& out, int index, int depth) const;

  const Scenario& s_;
  const MjcfOptions& options_;
  std::vector<BodySpec> bodies_;
  std::vector<GeomSpec> world_geoms_;
  std::vector<ActuatorSpec> actuators_;
  std::vector<WeldSpec> welds_;
  std::vector<std::pair<std::string, std::string>> excludes_;
  std::vector<std::pair<std::string, std::string>>
      force_sensors_;  // name, site
  std::vector<std::string> assets_;
  std::map<std::string, std::string> mesh_names_;  // key path|scale -> name
  std::string terrain_geom_type_;
};

std::string Builder::MeshAsset(const std::string& path, const Vector3d& scale,
                               const std::string& what) {
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
  assets_.push_back("    <mesh name=\"" + name + "\" file=\"" + Esc(abs) +
                    "\" scale=\"" + Vec(scale) + "\"/>\n");
  return name;
}

GeomSpec Builder::FrameGeom(const Frame& frame, const std::string& name) {
  GeomSpec g;
  g.name = name;
  g.mass = frame.mass;
  g.material = frame.material_name;
  if (frame.is_mesh()) {
    g.type = "mesh";
    g.mesh = MeshAsset(frame.shape, frame.scale, "frame '" + frame.guid + "'");
  } else {
    g.type = "box";
    g.size = frame.scale / 2;
  }
  return g;
}

void Builder::AddSensorModuleParts(const std::string& robot_name, int index,
                                   const SensorModule& sm, int body) {
  const Vector3d half = sm.size / 2;
  if (sm.force_sensor) {
    const ForceSensor& fsr = *sm.force_sensor;
    const Vector3d n = SensorFaceNormal(fsr.sensor_position);
    const double h = std::abs(n.dot(half));
    // The plate lies flat on the face: its thickness (size.z) along n.
    const Quaterniond local_q =
        Quaterniond::FromTwoVectors(Vector3d::UnitZ(), n);
    const Vector3d local_p = n * (h + fsr.size.z() / 2);
    const BodySpec& parent = bodies_[body];
    const int plate =
        AddBody(mjcf_names::PlateBody(robot_name, index),
                parent.pos + parent.quat * local_p, parent.quat * local_q);
    bodies_[plate].parent = body;
    bodies_[body].children.push_back(plate);
    GeomSpec g;
    g.name = bodies_[plate].name;
    g.type = "box";
    g.size = fsr.size / 2;
    g.mass = fsr.mass;
    g.material = fsr.material_name;
    bodies_[plate].geoms.push_back(g);
    bodies_[plate].sites.push_back({mjcf_names::ForceSite(robot_name, index),
                                    Vector3d::Zero(), Quaterniond::Identity()});
    force_sensors_.push_back({mjcf_names::ForceSensor(robot_name, index),
                              mjcf_names::ForceSite(robot_name, index)});
  }
  for (size_t k = 0; k < sm.distance_sensors.size(); ++k) {
    const DistanceSensor& ds = sm.distance_sensors[k];
    const Vector3d n = SensorFaceNormal(ds.sensor_position);
    const double h = std::abs(n.dot(half));
    Vector3d dir = ds.ray_direction;
    if (!(dir.norm() > 0) || !dir.allFinite()) dir = n;
    dir.normalize();
    const std::string site = mjcf_names::DistanceSite(robot_name, index, k);
    // Site x axis = ray direction, at the face centre.
    bodies_[body].sites.push_back(
        {site, n * h, Quaterniond::FromTwoVectors(Vector3d::UnitX(), dir)});
    if (ds.mass > 0 && ds.size.minCoeff() > 0) {
      // The sensor's own mass and look; it never collides (the module does).
      GeomSpec g;
      g.name = site;
      g.type = "box";
      g.size = ds.size / 2;
      g.pos = n * (h + std::abs(n.dot(ds.size)) / 2);
      g.mass = ds.mass;
      g.material = sm.material_name;
      g.collide = false;
      bodies_[body].geoms.push_back(g);
    }
  }
}

void Builder::AddRobot(const std::string& robot_name,
                       const std::vector<Module>& modules,
                       const std::vector<SensorModule>& sensor_modules,
                       const std::vector<Frame>& loose_frames,
                       const std::vector<Joint>& locks, bool servos) {
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
      bodies_[body].geoms.push_back(FrameGeom(frame, name));
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
    bodies_[body].geoms.push_back(FrameGeom(frame, name));
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
    e.servo = servos;
    edges.push_back(e);
  }
  // Locks between parts; a loose hinge joint becomes a passive hinge.
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
    if (e.hinge) {
      const BodySpec& lb = bodies_[nodes[e.a].body];
      const BodySpec& rb = bodies_[nodes[e.b].body];
      e.axis_world = lb.quat * Vector3d::UnitY();
      e.anchor_world = (lb.pos + rb.pos) / 2;
      e.joint_name = robot_name + "/j" + std::to_string(k) + "/hinge";
      e.lower = j.lower_range_limit;
      e.upper = j.upper_range_limit;
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
    for (int nr :
         {sensor_modules[k].left_mod_nr, sensor_modules[k].right_mod_nr}) {
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
        edges.push_back(e);
        break;
      }
    }
  }
  ConnectTree(robot_name, nodes, edges);
}

void Builder::ConnectTree(const std::string& robot_name,
                          std::vector<Node>& nodes,
                          const std::vector<Edge>& edges) {
  // Spanning forest: every hinge must be a tree edge (MuJoCo joints live in
  // the tree), locks join what the hinges left apart; any other lock
  // closes a loop and becomes a weld equality.
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
      if (ra == rb) {
        if (e.hinge) {
          throw std::logic_error("hinge '" + e.guid + "' was not validated");
        }
        welds_.push_back({robot_name + "/weld/" + e.guid,
                          bodies_[nodes[e.a].body].name,
                          bodies_[nodes[e.b].body].name});
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
  // Static parts first so their component hangs from the world.
  std::vector<int> order;
  for (size_t n = 0; n < nodes.size(); ++n)
    if (nodes[n].is_static) order.push_back(n);
  for (size_t n = 0; n < nodes.size(); ++n)
    if (!nodes[n].is_static) order.push_back(n);
  int component = 0;
  for (int root : order) {
    if (visited[root]) continue;
    BodySpec& rb = bodies_[nodes[root].body];
    if (!nodes[root].is_static) {
      rb.joint = JointKind::kFree;
      rb.joint_name = mjcf_names::RootJoint(robot_name, component);
    }
    ++component;
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
      actuators_.push_back({e.actuator_name, e.joint_name, e.max_vel});
    }
  }
}

void Builder::AddSceneObjects() {
  for (size_t i = 0; i < s_.scene_objects.size(); ++i) {
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
  std::string hfield = "    <hfield name=\"terrain\" size=\"" + Num(rx) + " " +
                       Num(ry) + " " + Num(top) + " " + Num(bottom) + "\"";
  if (options_.hfield_data_after_compile) {
    hfield += " nrow=\"" + std::to_string(image.rows) + "\" ncol=\"" +
              std::to_string(image.cols) + "\"";
  } else {
    std::string path;
    const bool png_file = TerrainImageIsFile(scene, s_.base_dir, &path) &&
                          fs::path(path).extension() == ".png";
    if (!png_file) {
      // Write the decoded image as an 8-bit grey PNG MuJoCo can read.
      cv::Mat grey(image.rows, image.cols, CV_32F,
                   const_cast<float*>(image.grey.data()));
      cv::Mat bytes;
      grey.convertTo(bytes, CV_8U, 255.0);
      std::vector<unsigned char> png;
      cv::imencode(".png", bytes, png);
      size_t h = 1469598103934665603ull;
      for (unsigned char c : png) h = (h ^ c) * 1099511628211ull;
      const fs::path dir = options_.asset_dir.empty()
                               ? fs::temp_directory_path()
                               : fs::path(options_.asset_dir);
      path = fs::absolute(dir / fmt::format("mrsim-terrain-{:016x}.png", h))
                 .string();
      std::ofstream out(path, std::ios::binary);
      out.write(reinterpret_cast<const char*>(png.data()), png.size());
      if (!out) {
        throw std::runtime_error("cannot write the terrain image to '" + path +
                                 "'");
      }
    }
    hfield += " file=\"" + Esc(path) + "\"";
  }
  assets_.push_back(hfield + "/>\n");
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

void Builder::WriteBody(std::ostringstream& out, int index, int depth) const {
  const BodySpec& b = bodies_[index];
  const std::string pad(2 * depth, ' ');
  Vector3d pos = b.pos;
  Quaterniond quat = b.quat;
  if (b.parent >= 0) {
    const BodySpec& p = bodies_[b.parent];
    pos = p.quat.conjugate() * (b.pos - p.pos);
    quat = Normalized(p.quat.conjugate() * b.quat);
  }
  out << pad << "<body name=\"" << Esc(b.name) << "\" pos=\"" << Vec(pos)
      << "\" quat=\"" << Quat(quat) << "\">\n";
  if (b.joint == JointKind::kFree) {
    out << pad << "  <freejoint name=\"" << Esc(b.joint_name) << "\"/>\n";
  } else if (b.joint == JointKind::kHinge) {
    // MuJoCo needs lower < upper; equal limits still pin the joint.
    const double lower = b.lower < b.upper ? b.lower : b.lower - 1e-9;
    const double upper = b.lower < b.upper ? b.upper : b.upper + 1e-9;
    out << pad << "  <joint name=\"" << Esc(b.joint_name)
        << "\" type=\"hinge\" pos=\"" << Vec(b.anchor) << "\" axis=\""
        << Vec(b.axis) << "\" limited=\"true\" range=\"" << Num(lower) << " "
        << Num(upper) << "\" armature=\"" << Num(ServoModel::kArmature)
        << "\"/>\n";
  }
  for (const GeomSpec& g : b.geoms) {
    out << pad << "  <geom name=\"" << Esc(g.name) << "\" type=\"" << g.type
        << "\"";
    if (g.type == "mesh") {
      out << " mesh=\"" << g.mesh << "\"";
    } else {
      out << " size=\"" << Vec(g.size) << "\"";
    }
    if (!g.pos.isZero()) out << " pos=\"" << Vec(g.pos) << "\"";
    if (!g.quat.isApprox(Quaterniond::Identity(), 0)) {
      out << " quat=\"" << Quat(g.quat) << "\"";
    }
    out << " mass=\"" << Num(g.mass) << "\" rgba=\"" << Rgba(g.material)
        << "\"";
    if (!g.collide) {
      out << " contype=\"0\" conaffinity=\"0\" group=\"1\"";
    } else {
      out << ContactGeomAttributes(s_, g.material);
    }
    out << "/>\n";
  }
  for (const SiteSpec& site : b.sites) {
    out << pad << "  <site name=\"" << Esc(site.name) << "\" pos=\""
        << Vec(site.pos) << "\" quat=\"" << Quat(site.quat)
        << "\" size=\"0.004\"/>\n";
  }
  for (int c : b.children) WriteBody(out, c, depth + 1);
  out << pad << "</body>\n";
}

std::string Builder::Build() {
  ValidateScenario(s_);
  for (size_t r = 0; r < s_.robots.size(); ++r) {
    const Robot& robot = s_.robots[r];
    const std::string name = mjcf_names::RobotName(s_, r);
    AddRobot(name, robot.modules, robot.sensor_modules, {}, robot.locks, true);
  }
  if (!s_.loose_frames.empty() || !s_.loose_sensor_modules.empty()) {
    AddRobot("loose", {}, s_.loose_sensor_modules, s_.loose_frames,
             s_.loose_joints, false);
  }
  AddSceneObjects();
  AddTerrain();

  const std::vector<int> weld = WeldGroups();
  int ngeom = static_cast<int>(world_geoms_.size());
  for (const BodySpec& b : bodies_) ngeom += b.geoms.size();

  std::ostringstream out;
  out << "<mujoco model=\"mrsim\">\n";
  out << "  <compiler angle=\"radian\" inertiafromgeom=\"true\"/>\n";
  out << "  <option timestep=\"" << Num(s_.settings.timestep) << "\" gravity=\""
      << Vec(s_.settings.gravity) << "\" integrator=\"Euler\"/>\n";
  const int ncon = std::max(200, 16 * ngeom);
  out << "  <size nconmax=\"" << ncon << "\" njmax=\"" << 4 * ncon << "\"/>\n";
  out << "  <visual><headlight ambient=\"0.4 0.4 0.4\"/></visual>\n";
  if (!assets_.empty()) {
    out << "  <asset>\n";
    for (const std::string& a : assets_) out << a;
    out << "  </asset>\n";
  }
  out << "  <worldbody>\n";
  out << "    <light name=\"sun\" directional=\"true\" pos=\"0 0 5\" "
         "dir=\"0 0 -1\"/>\n";
  for (const GeomSpec& g : world_geoms_) {
    out << "    <geom name=\"" << Esc(g.name) << "\" type=\"" << g.type << "\"";
    if (g.type == "hfield") {
      out << " hfield=\"terrain\"";
    } else {
      out << " size=\"" << Vec(g.size) << "\"";
    }
    out << " pos=\"" << Vec(g.pos) << "\" rgba=\"0.55 0.6 0.5 1\""
        << ContactGeomAttributes(s_, g.material) << "/>\n";
  }
  // Fluid regions as translucent boxes for viewers; sites, so rays and
  // contacts ignore them (their forces are applied by Physics).
  for (size_t i = 0; i < s_.fluid_regions.size(); ++i) {
    const FluidRegion& f = s_.fluid_regions[i];
    out << "    <site name=\"scene/fluid" << i << "\" type=\"box\" pos=\""
        << Vec(f.position) << "\" size=\"" << Vec(f.size / 2) << "\" rgba=\""
        << (f.kind == FluidKind::kWater ? "0.2 0.4 0.9 0.25"
                                        : "0.9 0.9 0.9 0.08")
        << "\"/>\n";
  }
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].parent < 0) WriteBody(out, b, 2);
  }
  out << "  </worldbody>\n";

  // Explicit pairs for material pairs of two different materials.
  struct CollGeom {
    std::string name, material, body;
    int group;
  };
  std::vector<CollGeom> coll;
  for (const GeomSpec& g : world_geoms_)
    coll.push_back({g.name, g.material, "", -1});
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
  std::ostringstream pairs;
  for (size_t i = 0; i < coll.size(); ++i) {
    for (size_t j = i + 1; j < coll.size(); ++j) {
      const CollGeom& a = coll[i];
      const CollGeom& b = coll[j];
      if (a.material == b.material) continue;
      const ContactFriction* cf =
          FindContactFriction(s_, a.material, b.material);
      if (!cf) continue;
      // Same filters MuJoCo applies to contacts it finds on its own.
      if (a.group == b.group || excluded.count({a.body, b.body})) continue;
      if (a.group >= 0 && b.group >= 0 &&
          (parent_group(a.group) == b.group ||
           parent_group(b.group) == a.group)) {
        continue;
      }
      pairs << "    <pair geom1=\"" << Esc(a.name) << "\" geom2=\""
            << Esc(b.name) << "\"" << ContactPairAttributes(s_, *cf) << "/>\n";
    }
  }
  const std::string pair_text = pairs.str();
  if (!pair_text.empty() || !excludes_.empty()) {
    out << "  <contact>\n";
    for (const auto& e : excludes_) {
      out << "    <exclude body1=\"" << Esc(e.first) << "\" body2=\""
          << Esc(e.second) << "\"/>\n";
    }
    out << pair_text;
    out << "  </contact>\n";
  }
  if (!welds_.empty()) {
    out << "  <equality>\n";
    for (const WeldSpec& w : welds_) {
      out << "    <weld name=\"" << Esc(w.name) << "\" body1=\"" << Esc(w.body1)
          << "\"";
      if (!w.body2.empty()) out << " body2=\"" << Esc(w.body2) << "\"";
      // As stiff as the timestep allows: a lock is meant to be rigid.
      out << " solref=\"" << Num(2 * s_.settings.timestep) << " 1\"/>\n";
    }
    out << "  </equality>\n";
  }
  if (!actuators_.empty()) {
    out << "  <actuator>\n";
    for (const ActuatorSpec& a : actuators_) {
      const double v = std::abs(a.max_vel);
      out << "    <velocity name=\"" << Esc(a.name) << "\" joint=\""
          << Esc(a.joint) << "\" kv=\"" << Num(ServoModel::kKv) << "\"";
      // Physics clamps the command itself; MuJoCo rejects an empty range.
      if (v > 0) {
        out << " ctrllimited=\"true\" ctrlrange=\"" << Num(-v) << " " << Num(v)
            << "\"";
      }
      out << " forcelimited=\"true\" forcerange=\""
          << Num(-ServoModel::kForceLimit) << " "
          << Num(ServoModel::kForceLimit) << "\"/>\n";
    }
    out << "  </actuator>\n";
  }
  if (!force_sensors_.empty()) {
    out << "  <sensor>\n";
    for (const auto& f : force_sensors_) {
      out << "    <force name=\"" << Esc(f.first) << "\" site=\""
          << Esc(f.second) << "\"/>\n";
    }
    out << "  </sensor>\n";
  }
  out << "</mujoco>\n";
  return out.str();
}

}  // namespace

std::string BuildMjcf(const Scenario& scenario) {
  return BuildMjcf(scenario, MjcfOptions{});
}

std::string BuildMjcf(const Scenario& scenario, const MjcfOptions& options) {
  return Builder(scenario, options).Build();
}

Eigen::Vector3d SensorFaceNormal(int sensor_position) {
  switch (sensor_position) {
    case 0:
      return -Vector3d::UnitZ();
    case 1:
      return Vector3d::UnitY();
    case 2:
      return Vector3d::UnitZ();
    case 3:
      return -Vector3d::UnitY();
    case 4:
      return Vector3d::UnitX();
    case 5:
      return -Vector3d::UnitX();
    default:
      throw std::out_of_range("sensorPosition must be 0..5, got " +
                              std::to_string(sensor_position));
  }
}

namespace mjcf_names {
std::string RobotName(const Scenario& scenario, int robot) {
  const std::string& name = scenario.robots.at(robot).name;
  return name.empty() ? "robot" + std::to_string(robot) : name;
}
std::string RootJoint(const std::string& robot, int component) {
  return robot + "/root" + (component == 0 ? "" : std::to_string(component));
}
std::string FrameBody(const std::string& robot, int module, int frame) {
  return robot + "/m" + std::to_string(module) + "/f" + std::to_string(frame);
}
std::string Hinge(const std::string& robot, int module) {
  return robot + "/m" + std::to_string(module) + "/hinge";
}
std::string Servo(const std::string& robot, int module) {
  return robot + "/m" + std::to_string(module) + "/servo";
}
std::string SensorModuleBody(const std::string& robot, int sm) {
  return robot + "/sm" + std::to_string(sm);
}
std::string PlateBody(const std::string& robot, int sm) {
  return SensorModuleBody(robot, sm) + "/plate";
}
std::string ForceSite(const std::string& robot, int sm) {
  return SensorModuleBody(robot, sm) + "/plate_site";
}
std::string ForceSensor(const std::string& robot, int sm) {
  return SensorModuleBody(robot, sm) + "/force";
}
std::string DistanceSite(const std::string& robot, int sm, int k) {
  return SensorModuleBody(robot, sm) + "/d" + std::to_string(k);
}
std::string SceneObject(int index) {
  return "scene/obj" + std::to_string(index);
}
std::string Terrain() { return "scene/terrain"; }
}  // namespace mjcf_names

}  // namespace mrsim

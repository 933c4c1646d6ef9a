#include "sim_core/scenario_xml.h"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "common/atomic_file.h"
#include "sim_core/embedded_mesh.h"
#include "sim_core/terrain.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

constexpr int kMaxDistanceSensors = 6;

// Element and attribute names without a namespace prefix ("xsi:nil" ->
// "nil"): readers ignore namespaces.
std::string LocalName(const char* name) {
  const char* colon = std::strrchr(name, ':');
  return colon ? std::string(colon + 1) : std::string(name);
}

std::string Trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::string Lower(std::string s) {
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Where something was declared, for errors found after parsing.
struct Location {
  int line = 0;
  std::string path;
};

// A joint end to resolve once the whole file is read. robot < 0: a loose
// joint, which may name any body in the scenario.
struct JointRef {
  std::string guid;
  Location where;
  int robot = -1;
};

class Reader;

// What an omitted field means, in the file's own frame: the model's
// defaults are Z-up, so a Unity file's defaults are those converted.
struct Defaults {
  Frame frame;
  ForceSensor force;
  DistanceSensor distance;
  SensorModule sensor_module;
  Scene scene;
  SceneObject object;
  FluidRegion fluid;
  SimulationSettings settings;
};

Defaults MakeDefaults(FrameConvention convention) {
  Defaults d;
  if (convention == FrameConvention::kZUp) return d;
  Scenario s;
  s.loose_frames = {Frame()};
  SensorModule sm;
  sm.force_sensor = ForceSensor();
  sm.distance_sensors = {DistanceSensor()};
  s.loose_sensor_modules = {sm};
  s.scene_objects = {SceneObject()};
  s.fluid_regions = {FluidRegion()};
  ConvertZUpToUnity(&s);
  d.frame = s.loose_frames[0];
  d.force = *s.loose_sensor_modules[0].force_sensor;
  d.distance = s.loose_sensor_modules[0].distance_sensors[0];
  d.sensor_module = s.loose_sensor_modules[0];
  d.sensor_module.force_sensor.reset();
  d.sensor_module.distance_sensors.clear();
  d.scene = s.scene;
  d.object = s.scene_objects[0];
  d.fluid = s.fluid_regions[0];
  d.settings = s.settings;
  return d;
}

// The child elements of one element, checked against what it may hold:
// unknown names and repeated singular fields are errors.
class Children {
 public:
  Children(const Reader& reader, const XMLElement* element, std::string path,
           std::vector<std::string> singles,
           std::vector<std::string> repeated = {});

  const XMLElement* element() const { return element_; }
  const std::string& path() const { return path_; }
  const XMLElement* Find(const std::string& name) const;
  const XMLElement* Need(const std::string& name) const;
  const std::vector<const XMLElement*>& List(const std::string& name) const;
  std::string PathOf(const std::string& name) const {
    return path_ + "/" + name;
  }
  std::string PathOf(const std::string& name, size_t index) const {
    return path_ + "/" + name + "[" + std::to_string(index + 1) + "]";
  }

  // Optional scalar fields: leave *out (its default) when absent.
  bool Get(const std::string& name, std::string* out) const;
  bool Get(const std::string& name, double* out) const;
  bool Get(const std::string& name, int* out) const;
  bool Get(const std::string& name, bool* out) const;
  bool Get(const std::string& name, Eigen::Vector3d* out) const;
  bool Get(const std::string& name, Eigen::Quaterniond* out) const;
  // Required fields: a missing one is an error naming it.
  template <typename T>
  void Require(const std::string& name, T* out) const {
    Need(name);
    Get(name, out);
  }

  // Fails at the named field (or this element when the field is absent).
  [[noreturn]] void FailAt(const std::string& name,
                           const std::string& what) const;
  void CheckPositive(const std::string& name, double value) const;
  void CheckNonNegative(const std::string& name, double value) const;
  void CheckPositive(const std::string& name,
                     const Eigen::Vector3d& value) const;

 private:
  const Reader& reader_;
  const XMLElement* element_;
  std::string path_;
  std::map<std::string, std::vector<const XMLElement*>> children_;
};

class Reader {
 public:
  Reader(std::string file, std::string base_dir)
      : file_(std::move(file)), base_dir_(std::move(base_dir)) {}

  Scenario Read(const std::string& xml);

  [[noreturn]] void Fail(const XMLElement* e, const std::string& path,
                         const std::string& what) const {
    Fail(e ? e->GetLineNum() : 0, path, what);
  }
  [[noreturn]] void Fail(int line, const std::string& path,
                         const std::string& what) const {
    throw ScenarioError(fmt::format("{}:{}: {}: {}", file_, line, path, what));
  }

  std::string Text(const XMLElement* e, const std::string& path) const;
  double Number(const XMLElement* e, const std::string& path) const;
  int Integer(const XMLElement* e, const std::string& path) const;
  bool Bool(const XMLElement* e, const std::string& path) const;
  Eigen::Vector3d Vector(const XMLElement* e, const std::string& path) const;
  Eigen::Quaterniond Quat(const XMLElement* e, const std::string& path) const;

 private:
  Robot ReadRobot(const XMLElement* e, const std::string& path, int index);
  Module ReadModule(const XMLElement* e, const std::string& path, int robot,
                    std::map<int, int>* numbers);
  Frame ReadFrame(const XMLElement* e, const std::string& path, int robot);
  Joint ReadJoint(const XMLElement* e, const std::string& path, int robot);
  // numbers: the robot's mod_Nr values (nullptr for a loose one).
  SensorModule ReadSensorModule(const XMLElement* e, const std::string& path,
                                int robot, const std::map<int, int>* numbers,
                                const std::string& robot_name);
  ForceSensor ReadForceSensor(const XMLElement* e, const std::string& path,
                              int robot);
  DistanceSensor ReadDistanceSensor(const XMLElement* e,
                                    const std::string& path, int robot);
  Scene ReadScene(const XMLElement* e, const std::string& path);
  SceneObject ReadSceneObject(const XMLElement* e, const std::string& path);
  ContactFriction ReadContactFriction(const XMLElement* e,
                                      const std::string& path);
  FluidRegion ReadFluidRegion(const XMLElement* e, const std::string& path);
  SimulationSettings ReadSettings(const XMLElement* e, const std::string& path);

  // The items of a list wrapper such as <modules>, all named `item`.
  std::vector<std::pair<const XMLElement*, std::string>> Items(
      const XMLElement* wrapper, const std::string& path,
      const std::string& item) const;
  // Records a guid (a body when `body_of_robot` is not kNone) and rejects
  // duplicates and empty guids.
  void AddGuid(const Children& c, const std::string& guid, int body_of_robot);
  void CheckJointRefs(const Scenario& scenario) const;
  void CheckConnected(const Scenario& scenario) const;
  void CheckImage(const Scene& scene, const XMLElement* e,
                  const std::string& path) const;
  void CheckMesh(const Frame& frame, const Children& c) const;
  std::string Resolve(const std::string& path) const;

  static constexpr int kNone = -3;
  static constexpr int kLoose = -1;

  std::string file_;
  std::string base_dir_;
  Defaults defaults_;
  std::map<std::string, Location> guids_;
  // Bodies (frames, sensor modules, sensors, scene objects) per robot
  // index; kLoose collects loose ones and scene objects.
  std::map<int, std::set<std::string>> bodies_;
  std::vector<JointRef> joint_refs_;
};

Children::Children(const Reader& reader, const XMLElement* element,
                   std::string path, std::vector<std::string> singles,
                   std::vector<std::string> repeated)
    : reader_(reader), element_(element), path_(std::move(path)) {
  for (const XMLElement* child = element->FirstChildElement(); child;
       child = child->NextSiblingElement()) {
    const std::string name = LocalName(child->Name());
    const bool single =
        std::find(singles.begin(), singles.end(), name) != singles.end();
    const bool many =
        std::find(repeated.begin(), repeated.end(), name) != repeated.end();
    if (!single && !many) {
      std::vector<std::string> all = singles;
      all.insert(all.end(), repeated.begin(), repeated.end());
      std::string expected;
      for (const std::string& n : all) {
        expected += (expected.empty() ? "<" : ", <") + n + ">";
      }
      reader_.Fail(
          child, path_ + "/" + name,
          "unknown element; expected one of " +
              (expected.empty() ? std::string("(no children)") : expected));
    }
    auto& list = children_[name];
    if (single && !list.empty()) {
      reader_.Fail(child, path_ + "/" + name,
                   fmt::format("given twice (first at line {})",
                               list.front()->GetLineNum()));
    }
    list.push_back(child);
  }
}

const XMLElement* Children::Find(const std::string& name) const {
  auto it = children_.find(name);
  return it == children_.end() ? nullptr : it->second.front();
}

const XMLElement* Children::Need(const std::string& name) const {
  const XMLElement* e = Find(name);
  if (!e) {
    reader_.Fail(element_, PathOf(name),
                 "missing; expected an element <" + name + ">");
  }
  return e;
}

const std::vector<const XMLElement*>& Children::List(
    const std::string& name) const {
  static const std::vector<const XMLElement*> kEmpty;
  auto it = children_.find(name);
  return it == children_.end() ? kEmpty : it->second;
}

bool Children::Get(const std::string& name, std::string* out) const {
  const XMLElement* e = Find(name);
  if (e) *out = reader_.Text(e, PathOf(name));
  return e;
}
bool Children::Get(const std::string& name, double* out) const {
  const XMLElement* e = Find(name);
  if (e) *out = reader_.Number(e, PathOf(name));
  return e;
}
bool Children::Get(const std::string& name, int* out) const {
  const XMLElement* e = Find(name);
  if (e) *out = reader_.Integer(e, PathOf(name));
  return e;
}
bool Children::Get(const std::string& name, bool* out) const {
  const XMLElement* e = Find(name);
  if (e) *out = reader_.Bool(e, PathOf(name));
  return e;
}
bool Children::Get(const std::string& name, Eigen::Vector3d* out) const {
  const XMLElement* e = Find(name);
  if (e) *out = reader_.Vector(e, PathOf(name));
  return e;
}
bool Children::Get(const std::string& name, Eigen::Quaterniond* out) const {
  const XMLElement* e = Find(name);
  if (e) *out = reader_.Quat(e, PathOf(name));
  return e;
}

void Children::FailAt(const std::string& name, const std::string& what) const {
  const XMLElement* e = Find(name);
  reader_.Fail(e ? e : element_, PathOf(name), what);
}

void Children::CheckPositive(const std::string& name, double value) const {
  if (!(value > 0)) {
    FailAt(name, fmt::format("expected a positive value, got {}", value));
  }
}

void Children::CheckNonNegative(const std::string& name, double value) const {
  if (!(value >= 0)) {
    FailAt(name, fmt::format("expected a value >= 0, got {}", value));
  }
}

void Children::CheckPositive(const std::string& name,
                             const Eigen::Vector3d& value) const {
  if (!(value.minCoeff() > 0)) {
    FailAt(name, fmt::format("expected positive x, y, z, got ({}, {}, {})",
                             value.x(), value.y(), value.z()));
  }
}

std::string Reader::Text(const XMLElement* e, const std::string& path) const {
  std::string text;
  for (const tinyxml2::XMLNode* n = e->FirstChild(); n; n = n->NextSibling()) {
    if (const XMLElement* child = n->ToElement()) {
      Fail(child, path,
           "expected text, got element <" + LocalName(child->Name()) + ">");
    }
    if (const tinyxml2::XMLText* t = n->ToText()) text += t->Value();
  }
  return text;
}

double Reader::Number(const XMLElement* e, const std::string& path) const {
  const std::string raw = Text(e, path);
  std::string text = Trim(raw);
  if (!text.empty() && text[0] == '+') text.erase(0, 1);
  double value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end ||
      !std::isfinite(value)) {
    Fail(e, path, "expected a number, got '" + raw + "'");
  }
  return value;
}

int Reader::Integer(const XMLElement* e, const std::string& path) const {
  const std::string raw = Text(e, path);
  std::string text = Trim(raw);
  if (!text.empty() && text[0] == '+') text.erase(0, 1);
  int value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) {
    Fail(e, path, "expected an integer, got '" + raw + "'");
  }
  return value;
}

bool Reader::Bool(const XMLElement* e, const std::string& path) const {
  const std::string raw = Text(e, path);
  const std::string text = Trim(raw);
  if (text == "true" || text == "1") return true;
  if (text == "false" || text == "0") return false;
  Fail(e, path, "expected true or false, got '" + raw + "'");
}

Eigen::Vector3d Reader::Vector(const XMLElement* e,
                               const std::string& path) const {
  Children c(*this, e, path, {"x", "y", "z"});
  Eigen::Vector3d v;
  c.Require("x", &v.x());
  c.Require("y", &v.y());
  c.Require("z", &v.z());
  return v;
}

Eigen::Quaterniond Reader::Quat(const XMLElement* e,
                                const std::string& path) const {
  Children c(*this, e, path, {"x", "y", "z", "w"});
  Eigen::Quaterniond q;
  c.Require("x", &q.x());
  c.Require("y", &q.y());
  c.Require("z", &q.z());
  c.Require("w", &q.w());
  if (!(q.coeffs().norm() > 1e-6)) {
    Fail(e, path, "expected a rotation quaternion, got all zeros");
  }
  return q;
}

std::vector<std::pair<const XMLElement*, std::string>> Reader::Items(
    const XMLElement* wrapper, const std::string& path,
    const std::string& item) const {
  std::vector<std::pair<const XMLElement*, std::string>> items;
  if (!wrapper) return items;
  Children c(*this, wrapper, path, {}, {item});
  const auto& list = c.List(item);
  for (size_t i = 0; i < list.size(); ++i) {
    items.emplace_back(list[i], c.PathOf(item, i));
  }
  return items;
}

std::string Reader::Resolve(const std::string& path) const {
  const fs::path p(path);
  if (p.is_absolute() || base_dir_.empty()) return path;
  return (fs::path(base_dir_) / p).string();
}

void Reader::AddGuid(const Children& c, const std::string& guid,
                     int body_of_robot) {
  if (guid.empty()) c.FailAt("guid", "expected a non-empty guid");
  const XMLElement* e = c.Find("guid");
  const Location here{e ? e->GetLineNum() : c.element()->GetLineNum(),
                      c.PathOf("guid")};
  auto [it, inserted] = guids_.emplace(guid, here);
  if (!inserted) {
    c.FailAt("guid", fmt::format("duplicate guid '{}' (first used at line "
                                 "{}, {})",
                                 guid, it->second.line, it->second.path));
  }
  if (body_of_robot != kNone) bodies_[body_of_robot].insert(guid);
}

Frame Reader::ReadFrame(const XMLElement* e, const std::string& path,
                        int robot) {
  Children c(*this, e, path,
             {"guid", "shape", "scale", "position", "rotation", "quatRotation",
              "mass", "isStatic", "materialName"});
  Frame f = defaults_.frame;
  c.Require("guid", &f.guid);
  AddGuid(c, f.guid, robot);
  c.Get("shape", &f.shape);
  c.Get("scale", &f.scale);
  c.Get("position", &f.position);
  c.Get("rotation", &f.rotation);
  c.Get("quatRotation", &f.quat_rotation);
  c.Get("mass", &f.mass);
  c.Get("isStatic", &f.is_static);
  c.Get("materialName", &f.material_name);
  if (f.shape.empty()) c.FailAt("shape", "expected Box or a mesh path");
  c.CheckPositive("scale", f.scale);
  if (f.is_static) {
    c.CheckNonNegative("mass", f.mass);
  } else {
    c.CheckPositive("mass", f.mass);
  }
  if (f.is_mesh()) CheckMesh(f, c);
  return f;
}

void Reader::CheckMesh(const Frame& frame, const Children& c) const {
  const std::string ext = Lower(fs::path(frame.shape).extension().string());
  if (ext != ".obj" && ext != ".stl") {
    c.FailAt("shape",
             "expected Box or a mesh file ending in .obj or .stl, "
             "got '" +
                 frame.shape + "'");
  }
  // A mesh carried inside the scenario (the optimiser's payload) names no
  // file; MuJoCo checks its bytes when the model is built.
  if (IsEmbeddedMesh(frame.shape)) return;
  const std::string resolved = Resolve(frame.shape);
  std::ifstream in(resolved, std::ios::binary);
  std::error_code ec;
  if (!in || !fs::is_regular_file(resolved, ec)) {
    c.FailAt("shape", "cannot read mesh file '" + resolved + "'");
  }
  const std::string bytes((std::istreambuf_iterator<char>(in)),
                          std::istreambuf_iterator<char>());
  bool ok = false;
  if (ext == ".obj") {
    std::istringstream lines(bytes);
    std::string line;
    bool vertex = false, face = false;
    while (std::getline(lines, line)) {
      if (line.rfind("v ", 0) == 0) vertex = true;
      if (line.rfind("f ", 0) == 0) face = true;
    }
    ok = vertex && face;
  } else if (bytes.size() >= 84) {
    std::uint32_t triangles = 0;
    std::memcpy(&triangles, bytes.data() + 80, 4);
    ok = triangles > 0 && bytes.size() == 84 + 50ull * triangles;
    if (!ok) {
      ok = bytes.rfind("solid", 0) == 0 &&
           bytes.find("facet") != std::string::npos;
    }
  } else {
    ok = bytes.rfind("solid", 0) == 0 &&
         bytes.find("facet") != std::string::npos;
  }
  if (!ok) {
    c.FailAt("shape", "mesh file '" + resolved + "' is not a valid " +
                          (ext == ".obj" ? "OBJ (needs v and f lines)"
                                         : "STL (binary or ASCII)"));
  }
}

Joint Reader::ReadJoint(const XMLElement* e, const std::string& path,
                        int robot) {
  Children c(*this, e, path,
             {"guid", "leftFrameGuid", "rightFrameGuid", "type",
              "lowerRangeLimit", "upperRangeLimit", "Kp", "max_vel"});
  Joint j;
  c.Require("guid", &j.guid);
  c.Require("leftFrameGuid", &j.left_frame_guid);
  c.Require("rightFrameGuid", &j.right_frame_guid);
  std::string type;
  c.Require("type", &type);
  if (type == "Hinge") {
    j.type = JointType::kHinge;
  } else if (type == "Lock") {
    j.type = JointType::kLock;
  } else {
    c.FailAt("type", "expected Hinge or Lock, got '" + type + "'");
  }
  c.Get("lowerRangeLimit", &j.lower_range_limit);
  c.Get("upperRangeLimit", &j.upper_range_limit);
  c.Get("Kp", &j.kp);
  c.Get("max_vel", &j.max_vel);
  AddGuid(c, j.guid, kNone);
  if (j.lower_range_limit > j.upper_range_limit) {
    c.FailAt("lowerRangeLimit",
             fmt::format("lower limit {} is above the upper limit {}",
                         j.lower_range_limit, j.upper_range_limit));
  }
  c.CheckNonNegative("Kp", j.kp);
  c.CheckPositive("max_vel", j.max_vel);
  if (j.left_frame_guid == j.right_frame_guid) {
    c.FailAt("rightFrameGuid",
             "a joint must join two different parts, both "
             "ends are '" +
                 j.left_frame_guid + "'");
  }
  for (const char* end : {"leftFrameGuid", "rightFrameGuid"}) {
    const XMLElement* ee = c.Find(end);
    joint_refs_.push_back(
        {Text(ee, c.PathOf(end)), {ee->GetLineNum(), c.PathOf(end)}, robot});
  }
  return j;
}

Module Reader::ReadModule(const XMLElement* e, const std::string& path,
                          int robot, std::map<int, int>* numbers) {
  Children c(*this, e, path, {"mod_Nr", "position", "axis", "frames", "joint"});
  Module m;
  c.Require("mod_Nr", &m.mod_nr);
  auto [first, inserted] =
      numbers->emplace(m.mod_nr, c.Find("mod_Nr")->GetLineNum());
  if (!inserted) {
    c.FailAt("mod_Nr", fmt::format("duplicate mod_Nr {} (first at line {})",
                                   m.mod_nr, first->second));
  }
  c.Get("position", &m.position);
  std::string axis;
  c.Require("axis", &axis);
  if (axis == "Pitch") {
    m.axis = Axis::kPitch;
  } else if (axis == "Yaw") {
    m.axis = Axis::kYaw;
  } else {
    c.FailAt("axis", "expected Pitch or Yaw, got '" + axis + "'");
  }
  const auto frames = Items(c.Need("frames"), c.PathOf("frames"), "Frame");
  if (frames.size() != 2) {
    c.FailAt("frames",
             fmt::format("expected 2 <Frame> elements, got {}", frames.size()));
  }
  for (size_t i = 0; i < 2; ++i) {
    m.frames[i] = ReadFrame(frames[i].first, frames[i].second, robot);
  }
  const XMLElement* joint = c.Need("joint");
  m.joint = ReadJoint(joint, c.PathOf("joint"), robot);
  if (m.joint.type != JointType::kHinge) {
    c.FailAt("joint", "a module's joint must be of type Hinge");
  }
  return m;
}

ForceSensor Reader::ReadForceSensor(const XMLElement* e,
                                    const std::string& path, int robot) {
  Children c(*this, e, path,
             {"guid", "forceValue", "sensorPosition", "position", "rotation",
              "materialName", "mass", "size"});
  ForceSensor s = defaults_.force;
  c.Require("guid", &s.guid);
  AddGuid(c, s.guid, robot);
  c.Get("forceValue", &s.force_value);
  c.Get("sensorPosition", &s.sensor_position);
  c.Get("position", &s.position);
  c.Get("rotation", &s.rotation);
  c.Get("materialName", &s.material_name);
  c.Get("mass", &s.mass);
  c.Get("size", &s.size);
  if (s.sensor_position < 0 || s.sensor_position > 3) {
    c.FailAt("sensorPosition",
             fmt::format("expected 0..3 (bottom, left, top, right), got {}",
                         s.sensor_position));
  }
  c.CheckPositive("mass", s.mass);
  c.CheckPositive("size", s.size);
  return s;
}

DistanceSensor Reader::ReadDistanceSensor(const XMLElement* e,
                                          const std::string& path, int robot) {
  Children c(
      *this, e, path,
      {"guid", "sensorPosition", "position", "rotation", "quatRotation", "mass",
       "size", "max_rayDistance", "ray_Direction", "ray_Resolution"});
  DistanceSensor s = defaults_.distance;
  c.Require("guid", &s.guid);
  AddGuid(c, s.guid, robot);
  c.Get("sensorPosition", &s.sensor_position);
  c.Get("position", &s.position);
  c.Get("rotation", &s.rotation);
  c.Get("quatRotation", &s.quat_rotation);
  c.Get("mass", &s.mass);
  c.Get("size", &s.size);
  c.Get("max_rayDistance", &s.max_ray_distance);
  c.Get("ray_Direction", &s.ray_direction);
  c.Get("ray_Resolution", &s.ray_resolution);
  if (s.sensor_position < 0 || s.sensor_position > 5) {
    c.FailAt("sensorPosition",
             fmt::format("expected 0..5 (bottom, left, top, right, front, "
                         "back), got {}",
                         s.sensor_position));
  }
  c.CheckPositive("mass", s.mass);
  c.CheckPositive("size", s.size);
  c.CheckPositive("max_rayDistance", s.max_ray_distance);
  if (!(s.ray_direction.norm() > 1e-9)) {
    c.FailAt("ray_Direction", "expected a non-zero direction");
  }
  if (s.ray_resolution < 1) {
    c.FailAt("ray_Resolution",
             fmt::format("expected at least 1, got {}", s.ray_resolution));
  }
  return s;
}

SensorModule Reader::ReadSensorModule(const XMLElement* e,
                                      const std::string& path, int robot,
                                      const std::map<int, int>* numbers,
                                      const std::string& robot_name) {
  Children c(*this, e, path,
             {"guid", "leftMod_Nr", "rightMod_Nr", "forceSensorLock",
              "forceLockPosition", "distanceSensors", "distanceLockPosition",
              "distanceSensorLocks", "position", "rotation", "size",
              "quatRotation", "mass", "materialName"},
             {"forceSensor"});
  SensorModule s = defaults_.sensor_module;
  c.Require("guid", &s.guid);
  AddGuid(c, s.guid, robot);
  c.Get("leftMod_Nr", &s.left_mod_nr);
  c.Get("rightMod_Nr", &s.right_mod_nr);
  for (const auto& [field, nr] :
       {std::make_pair("leftMod_Nr", s.left_mod_nr),
        std::make_pair("rightMod_Nr", s.right_mod_nr)}) {
    if (nr < -1 || (numbers && nr != -1 && !numbers->count(nr))) {
      c.FailAt(field, fmt::format("no module with mod_Nr {} in robot '{}' "
                                  "(use -1 for the chain end)",
                                  nr, robot_name));
    }
  }
  // XmlSerializer may write a null reference as xsi:nil="true".
  auto is_nil = [](const XMLElement* x) {
    for (const tinyxml2::XMLAttribute* a = x->FirstAttribute(); a;
         a = a->Next()) {
      if (LocalName(a->Name()) == "nil" && Trim(a->Value()) == "true") {
        return true;
      }
    }
    return false;
  };
  const auto& force = c.List("forceSensor");
  for (size_t i = 0; i < force.size(); ++i) {
    if (is_nil(force[i])) continue;
    if (s.force_sensor) {
      Fail(force[i], c.PathOf("forceSensor"),
           "more than one force sensor on a sensor module (at most 1)");
    }
    const std::string fpath = c.PathOf("forceSensor");
    s.force_sensor = ReadForceSensor(force[i], fpath, robot);
  }
  if (const XMLElement* lock = c.Find("forceSensorLock")) {
    if (!is_nil(lock)) {
      s.force_sensor_lock = ReadJoint(lock, c.PathOf("forceSensorLock"), robot);
    }
  }
  c.Get("forceLockPosition", &s.force_lock_position);
  const auto distance = Items(c.Find("distanceSensors"),
                              c.PathOf("distanceSensors"), "DistanceSensor");
  for (size_t i = 0; i < distance.size(); ++i) {
    if (i == kMaxDistanceSensors) {
      Fail(distance[i].first, distance[i].second,
           fmt::format("more than {} distance sensors on a sensor module",
                       kMaxDistanceSensors));
    }
    s.distance_sensors.push_back(
        ReadDistanceSensor(distance[i].first, distance[i].second, robot));
  }
  c.Get("distanceLockPosition", &s.distance_lock_position);
  for (const auto& [lock, lpath] :
       Items(c.Find("distanceSensorLocks"), c.PathOf("distanceSensorLocks"),
             "Joint")) {
    s.distance_sensor_locks.push_back(ReadJoint(lock, lpath, robot));
  }
  c.Get("position", &s.position);
  c.Get("rotation", &s.rotation);
  c.Get("size", &s.size);
  c.Get("quatRotation", &s.quat_rotation);
  c.Get("mass", &s.mass);
  c.Get("materialName", &s.material_name);
  c.CheckPositive("size", s.size);
  c.CheckPositive("mass", s.mass);
  return s;
}

Robot Reader::ReadRobot(const XMLElement* e, const std::string& path,
                        int index) {
  Children c(*this, e, path, {"name", "modules", "sensorModules", "locks"});
  Robot r;
  r.name = "robot" + std::to_string(index);
  c.Get("name", &r.name);
  const bool name_ok =
      !r.name.empty() && std::all_of(r.name.begin(), r.name.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' ||
               ch == '-' || ch == '.';
      });
  if (!name_ok) {
    c.FailAt("name",
             "expected a robot name of letters, digits, '_', '-' "
             "or '.', got '" +
                 r.name + "'");
  }
  const auto modules = Items(c.Need("modules"), c.PathOf("modules"), "Module");
  if (modules.empty()) {
    c.FailAt("modules", "expected at least one <Module>");
  }
  std::map<int, int> numbers;  // mod_Nr -> line
  for (const auto& [me, mpath] : modules) {
    r.modules.push_back(ReadModule(me, mpath, index, &numbers));
  }
  for (const auto& [se, spath] :
       Items(c.Find("sensorModules"), c.PathOf("sensorModules"),
             "SensorModule")) {
    r.sensor_modules.push_back(
        ReadSensorModule(se, spath, index, &numbers, r.name));
  }
  for (const auto& [le, lpath] :
       Items(c.Find("locks"), c.PathOf("locks"), "Joint")) {
    r.locks.push_back(ReadJoint(le, lpath, index));
  }
  return r;
}

Scene Reader::ReadScene(const XMLElement* e, const std::string& path) {
  Children c(*this, e, path,
             {"guid", "height_Image", "position", "materialName", "height",
              "metersPerPixel"});
  Scene s = defaults_.scene;
  c.Get("guid", &s.guid);
  if (!s.guid.empty()) AddGuid(c, s.guid, kNone);
  c.Get("height_Image", &s.height_image);
  c.Get("position", &s.position);
  c.Get("materialName", &s.material_name);
  c.Get("height", &s.height);
  c.Get("metersPerPixel", &s.meters_per_pixel);
  c.CheckNonNegative("height", s.height);
  c.CheckPositive("metersPerPixel", s.meters_per_pixel);
  if (!s.height_image.empty()) {
    CheckImage(s, c.Find("height_Image"), c.PathOf("height_Image"));
  }
  return s;
}

// The physics decodes the image the same way (sim_core/terrain.h), so a
// file that validates also loads.
void Reader::CheckImage(const Scene& scene, const XMLElement* e,
                        const std::string& path) const {
  try {
    LoadTerrainImage(scene, base_dir_);
  } catch (const std::exception& err) {
    Fail(e, path, std::string("cannot read the height image: ") + err.what());
  }
}

SceneObject Reader::ReadSceneObject(const XMLElement* e,
                                    const std::string& path) {
  Children c(*this, e, path,
             {"guid", "size", "position", "rotation", "quatRotation",
              "materialName", "shape", "mass", "isStatic"});
  SceneObject o = defaults_.object;
  c.Require("guid", &o.guid);
  AddGuid(c, o.guid, kLoose);
  c.Get("size", &o.size);
  c.Get("position", &o.position);
  c.Get("rotation", &o.rotation);
  c.Get("quatRotation", &o.quat_rotation);
  c.Get("materialName", &o.material_name);
  std::string shape;
  c.Require("shape", &shape);
  if (shape == "Box") {
    o.shape = PrimitiveShape::kBox;
  } else if (shape == "Sphere") {
    o.shape = PrimitiveShape::kSphere;
  } else if (shape == "Cylinder") {
    o.shape = PrimitiveShape::kCylinder;
  } else if (shape == "Capsule") {
    o.shape = PrimitiveShape::kCapsule;
  } else {
    c.FailAt("shape",
             "expected Box, Sphere, Cylinder or Capsule, got '" + shape + "'");
  }
  c.Get("mass", &o.mass);
  c.Get("isStatic", &o.is_static);
  c.CheckPositive("size", o.size);
  if (o.is_static) {
    c.CheckNonNegative("mass", o.mass);
  } else {
    c.CheckPositive("mass", o.mass);
  }
  return o;
}

ContactFriction Reader::ReadContactFriction(const XMLElement* e,
                                            const std::string& path) {
  Children c(
      *this, e, path,
      {"material1", "material2", "restitution", "friction", "youngsModulus"});
  ContactFriction f;
  c.Require("material1", &f.material1);
  c.Require("material2", &f.material2);
  c.Get("restitution", &f.restitution);
  c.Get("friction", &f.friction);
  c.Get("youngsModulus", &f.youngs_modulus);
  if (f.material1.empty()) c.FailAt("material1", "expected a material name");
  if (f.material2.empty()) c.FailAt("material2", "expected a material name");
  if (!(f.restitution >= 0 && f.restitution <= 1)) {
    c.FailAt("restitution",
             fmt::format("expected 0..1, got {}", f.restitution));
  }
  c.CheckNonNegative("friction", f.friction);
  c.CheckPositive("youngsModulus", f.youngs_modulus);
  return f;
}

FluidRegion Reader::ReadFluidRegion(const XMLElement* e,
                                    const std::string& path) {
  Children c(
      *this, e, path,
      {"guid", "kind", "position", "size", "density", "viscosity", "velocity"});
  FluidRegion r = defaults_.fluid;
  c.Get("guid", &r.guid);
  if (!r.guid.empty()) AddGuid(c, r.guid, kNone);
  std::string kind;
  c.Require("kind", &kind);
  if (kind == "Water") {
    r.kind = FluidKind::kWater;
    r.density = 1000.0;
    r.viscosity = 0.0009;
  } else if (kind == "Air") {
    r.kind = FluidKind::kAir;
    r.density = 1.2;
    r.viscosity = 1.8e-5;
  } else {
    c.FailAt("kind", "expected Water or Air, got '" + kind + "'");
  }
  c.Get("position", &r.position);
  c.Get("size", &r.size);
  c.Get("density", &r.density);
  c.Get("viscosity", &r.viscosity);
  c.Get("velocity", &r.velocity);
  c.CheckPositive("size", r.size);
  c.CheckPositive("density", r.density);
  c.CheckNonNegative("viscosity", r.viscosity);
  return r;
}

SimulationSettings Reader::ReadSettings(const XMLElement* e,
                                        const std::string& path) {
  Children c(*this, e, path, {"timestep", "gravity"});
  SimulationSettings s = defaults_.settings;
  c.Get("timestep", &s.timestep);
  c.Get("gravity", &s.gravity);
  c.CheckPositive("timestep", s.timestep);
  return s;
}

void Reader::CheckJointRefs(const Scenario& scenario) const {
  std::set<std::string> all;
  for (const auto& [robot, names] : bodies_)
    all.insert(names.begin(), names.end());
  for (const JointRef& ref : joint_refs_) {
    if (ref.robot >= 0) {
      auto it = bodies_.find(ref.robot);
      if (it == bodies_.end() || !it->second.count(ref.guid)) {
        const bool elsewhere = all.count(ref.guid) > 0;
        Fail(ref.where.line, ref.where.path,
             fmt::format("no frame, sensor module or sensor with guid '{}' "
                         "in robot '{}'{}",
                         ref.guid, scenario.robots[ref.robot].name,
                         elsewhere ? " (it belongs to another part of the "
                                     "scenario; joints of a robot join only "
                                     "its own parts)"
                                   : ""));
      }
    } else if (!all.count(ref.guid)) {
      Fail(ref.where.line, ref.where.path,
           fmt::format("no frame, sensor module, sensor or scene object with "
                       "guid '{}'",
                       ref.guid));
    }
  }
}

// Every part of a robot must hang together through its joints, or the
// physics would get several loose pieces under one name. As in the physics
// (mjcf_builder.cc): sensors belong to their sensor module, and a sensor
// module that no lock names is locked to its neighbouring modules.
void Reader::CheckConnected(const Scenario& scenario) const {
  for (size_t r = 0; r < scenario.robots.size(); ++r) {
    const Robot& robot = scenario.robots[r];
    auto it = bodies_.find(static_cast<int>(r));
    if (it == bodies_.end()) continue;
    std::map<std::string, std::string> parent;
    std::function<std::string(const std::string&)> root =
        [&](const std::string& x) -> std::string {
      auto p = parent.find(x);
      if (p == parent.end() || p->second == x) return x;
      return p->second = root(p->second);
    };
    for (const std::string& b : it->second) parent[b] = b;
    auto join = [&](const std::string& a, const std::string& b) {
      parent[root(a)] = root(b);
    };
    std::set<std::string> named;  // parts some hinge or lock names
    auto join_joint = [&](const Joint& j) {
      join(j.left_frame_guid, j.right_frame_guid);
      named.insert(j.left_frame_guid);
      named.insert(j.right_frame_guid);
    };
    for (const Module& m : robot.modules) join_joint(m.joint);
    for (const Joint& j : robot.locks) join_joint(j);
    for (const SensorModule& sm : robot.sensor_modules) {
      if (sm.force_sensor) join(sm.force_sensor->guid, sm.guid);
      for (const DistanceSensor& d : sm.distance_sensors) join(d.guid, sm.guid);
      if (named.count(sm.guid)) continue;
      for (const Module& m : robot.modules) {
        if (m.mod_nr == sm.left_mod_nr || m.mod_nr == sm.right_mod_nr) {
          join(m.frames[0].guid, sm.guid);
          join(m.frames[1].guid, sm.guid);
        }
      }
    }
    const std::string first = root(robot.modules.front().frames[0].guid);
    for (const std::string& b : it->second) {
      if (root(b) != first) {
        const Location& where = guids_.at(b);
        Fail(where.line, where.path,
             fmt::format("part '{}' is not joined to the rest of robot '{}' "
                         "(expected a hinge or a lock in <locks> linking it)",
                         b, robot.name));
      }
    }
  }
}

Scenario Reader::Read(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    std::string detail = doc.ErrorStr() ? doc.ErrorStr() : doc.ErrorName();
    throw ScenarioError(fmt::format("{}:{}: Scenario: malformed XML: {}", file_,
                                    doc.ErrorLineNum(), detail));
  }
  const XMLElement* root = doc.RootElement();
  if (!root) {
    throw ScenarioError(file_ + ":1: Scenario: expected a <Scenario> element");
  }
  if (LocalName(root->Name()) != "Scenario") {
    Fail(root, LocalName(root->Name()), "expected the root element <Scenario>");
  }
  const std::string kRoot = "Scenario";
  FrameConvention frame = FrameConvention::kZUp;
  for (const tinyxml2::XMLAttribute* a = root->FirstAttribute(); a;
       a = a->Next()) {
    if (std::string(a->Name()) != "frame") continue;  // xmlns:* and others
    const std::string value = a->Value();
    if (value == "z-up") {
      frame = FrameConvention::kZUp;
    } else if (value == "unity-y-up") {
      frame = FrameConvention::kUnityYUp;
    } else {
      Fail(root, kRoot + "/@frame",
           "expected frame=\"z-up\" or frame=\"unity-y-up\", got '" + value +
               "'");
    }
  }
  Children c(*this, root, kRoot,
             {"scene", "sceneObjects", "contactFrictions", "fluidRegions",
              "settings", "frames", "joints", "sensorModules"},
             {"robot"});
  defaults_ = MakeDefaults(frame);
  Scenario s;
  s.base_dir = base_dir_;
  s.scene = defaults_.scene;
  s.settings = defaults_.settings;
  const auto& robots = c.List("robot");
  std::map<std::string, Location> names;
  for (size_t i = 0; i < robots.size(); ++i) {
    const std::string rpath = c.PathOf("robot", i);
    s.robots.push_back(ReadRobot(robots[i], rpath, static_cast<int>(i)));
    auto [it, inserted] = names.emplace(
        s.robots.back().name, Location{robots[i]->GetLineNum(), rpath});
    if (!inserted) {
      const XMLElement* name = robots[i]->FirstChildElement();
      while (name && LocalName(name->Name()) != "name") {
        name = name->NextSiblingElement();
      }
      Fail(name ? name : robots[i], rpath + "/name",
           fmt::format("duplicate robot name '{}' (first at line {}); robot "
                       "names must be unique",
                       s.robots.back().name, it->second.line));
    }
  }
  if (const XMLElement* scene = c.Find("scene")) {
    s.scene = ReadScene(scene, c.PathOf("scene"));
  }
  for (const auto& [e, path] :
       Items(c.Find("sceneObjects"), c.PathOf("sceneObjects"), "SceneObject")) {
    s.scene_objects.push_back(ReadSceneObject(e, path));
  }
  std::map<std::pair<std::string, std::string>, int> pairs;
  for (const auto& [e, path] :
       Items(c.Find("contactFrictions"), c.PathOf("contactFrictions"),
             "ContactFriction")) {
    s.contact_frictions.push_back(ReadContactFriction(e, path));
    const ContactFriction& f = s.contact_frictions.back();
    auto key = std::minmax(f.material1, f.material2);
    auto [it, inserted] =
        pairs.emplace(std::make_pair(key.first, key.second), e->GetLineNum());
    if (!inserted) {
      Fail(e, path,
           fmt::format("second ContactFriction for materials '{}'/'{}' "
                       "(first at line {})",
                       f.material1, f.material2, it->second));
    }
  }
  for (const auto& [e, path] :
       Items(c.Find("fluidRegions"), c.PathOf("fluidRegions"), "FluidRegion")) {
    s.fluid_regions.push_back(ReadFluidRegion(e, path));
  }
  if (const XMLElement* settings = c.Find("settings")) {
    s.settings = ReadSettings(settings, c.PathOf("settings"));
  }
  for (const auto& [e, path] :
       Items(c.Find("frames"), c.PathOf("frames"), "Frame")) {
    s.loose_frames.push_back(ReadFrame(e, path, kLoose));
  }
  for (const auto& [e, path] :
       Items(c.Find("sensorModules"), c.PathOf("sensorModules"),
             "SensorModule")) {
    s.loose_sensor_modules.push_back(
        ReadSensorModule(e, path, kLoose, nullptr, ""));
  }
  for (const auto& [e, path] :
       Items(c.Find("joints"), c.PathOf("joints"), "Joint")) {
    s.loose_joints.push_back(ReadJoint(e, path, kLoose));
  }
  CheckJointRefs(s);
  CheckConnected(s);
  if (frame == FrameConvention::kUnityYUp) ConvertUnityToZUp(&s);
  return s;
}

// Deterministic XmlSerializer-style output: two-space indentation, every
// field written, numbers in the shortest form that reads back exactly.
class Writer {
 public:
  std::string Take() { return std::move(out_); }

  void Open(const std::string& name, const std::string& attributes = "") {
    Indent();
    out_ += "<" + name + attributes + ">\n";
    ++depth_;
  }
  void Close(const std::string& name) {
    --depth_;
    Indent();
    out_ += "</" + name + ">\n";
  }
  void Empty(const std::string& name, const std::string& attributes = "") {
    Indent();
    out_ += "<" + name + attributes + " />\n";
  }
  void Text(const std::string& name, const std::string& text) {
    if (text.empty()) {
      Empty(name);
      return;
    }
    Indent();
    out_ += "<" + name + ">" + Escape(text) + "</" + name + ">\n";
  }
  void Number(const std::string& name, double value) {
    Text(name, fmt::format("{}", value));
  }
  void Integer(const std::string& name, int value) {
    Text(name, std::to_string(value));
  }
  void Bool(const std::string& name, bool value) {
    Text(name, value ? "true" : "false");
  }
  void Vector(const std::string& name, const Eigen::Vector3d& v) {
    Open(name);
    Number("x", v.x());
    Number("y", v.y());
    Number("z", v.z());
    Close(name);
  }
  void Quat(const std::string& name, const Eigen::Quaterniond& q) {
    Open(name);
    Number("x", q.x());
    Number("y", q.y());
    Number("z", q.z());
    Number("w", q.w());
    Close(name);
  }
  // A list wrapper: <name xmlns="Assembly">items</name>, or <name /> when
  // empty.
  template <typename T, typename F>
  void List(const std::string& name, const std::vector<T>& items, F write,
            bool assembly = true) {
    const std::string attributes = assembly ? " xmlns=\"Assembly\"" : "";
    if (items.empty()) {
      Empty(name, attributes);
      return;
    }
    Open(name, attributes);
    for (const T& item : items) write(item);
    Close(name);
  }

 private:
  void Indent() { out_.append(2 * depth_, ' '); }
  static std::string Escape(const std::string& s) {
    std::string r;
    for (char ch : s) {
      switch (ch) {
        case '&':
          r += "&amp;";
          break;
        case '<':
          r += "&lt;";
          break;
        case '>':
          r += "&gt;";
          break;
        case '"':
          r += "&quot;";
          break;
        case '\'':
          r += "&apos;";
          break;
        case '\r':
          r += "&#xD;";
          break;
        default:
          r += ch;
      }
    }
    return r;
  }

  std::string out_;
  int depth_ = 0;
};

void WriteFrame(Writer& w, const Frame& f, const std::string& tag = "Frame") {
  w.Open(tag);
  w.Text("guid", f.guid);
  w.Text("shape", f.shape);
  w.Vector("scale", f.scale);
  w.Vector("position", f.position);
  w.Vector("rotation", f.rotation);
  w.Quat("quatRotation", f.quat_rotation);
  w.Number("mass", f.mass);
  w.Bool("isStatic", f.is_static);
  w.Text("materialName", f.material_name);
  w.Close(tag);
}

void WriteJoint(Writer& w, const Joint& j, const std::string& tag = "Joint") {
  w.Open(tag);
  w.Text("guid", j.guid);
  w.Text("leftFrameGuid", j.left_frame_guid);
  w.Text("rightFrameGuid", j.right_frame_guid);
  w.Text("type", ToString(j.type));
  w.Number("lowerRangeLimit", j.lower_range_limit);
  w.Number("upperRangeLimit", j.upper_range_limit);
  w.Number("Kp", j.kp);
  w.Number("max_vel", j.max_vel);
  w.Close(tag);
}

void WriteSensorModule(Writer& w, const SensorModule& s) {
  w.Open("SensorModule");
  w.Text("guid", s.guid);
  w.Integer("leftMod_Nr", s.left_mod_nr);
  w.Integer("rightMod_Nr", s.right_mod_nr);
  if (s.force_sensor) {
    const ForceSensor& f = *s.force_sensor;
    w.Open("forceSensor");
    w.Text("guid", f.guid);
    w.Number("forceValue", f.force_value);
    w.Integer("sensorPosition", f.sensor_position);
    w.Vector("position", f.position);
    w.Quat("rotation", f.rotation);
    w.Text("materialName", f.material_name);
    w.Number("mass", f.mass);
    w.Vector("size", f.size);
    w.Close("forceSensor");
  }
  if (s.force_sensor_lock)
    WriteJoint(w, *s.force_sensor_lock, "forceSensorLock");
  w.Vector("forceLockPosition", s.force_lock_position);
  w.List("distanceSensors", s.distance_sensors, [&](const DistanceSensor& d) {
    w.Open("DistanceSensor");
    w.Text("guid", d.guid);
    w.Integer("sensorPosition", d.sensor_position);
    w.Vector("position", d.position);
    w.Vector("rotation", d.rotation);
    w.Quat("quatRotation", d.quat_rotation);
    w.Number("mass", d.mass);
    w.Vector("size", d.size);
    w.Number("max_rayDistance", d.max_ray_distance);
    w.Vector("ray_Direction", d.ray_direction);
    w.Integer("ray_Resolution", d.ray_resolution);
    w.Close("DistanceSensor");
  });
  w.Vector("distanceLockPosition", s.distance_lock_position);
  w.List("distanceSensorLocks", s.distance_sensor_locks,
         [&](const Joint& j) { WriteJoint(w, j); });
  w.Vector("position", s.position);
  w.Vector("rotation", s.rotation);
  w.Vector("size", s.size);
  w.Quat("quatRotation", s.quat_rotation);
  w.Number("mass", s.mass);
  w.Text("materialName", s.material_name);
  w.Close("SensorModule");
}

std::string Write(const Scenario& s, FrameConvention frame) {
  Writer w;
  w.Open("Scenario",
         fmt::format(" xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\""
                     " xmlns:xsd=\"http://www.w3.org/2001/XMLSchema\""
                     " frame=\"{}\"",
                     ToString(frame)));
  for (const Robot& r : s.robots) {
    w.Open("robot");
    w.Text("name", r.name);
    w.List("modules", r.modules, [&](const Module& m) {
      w.Open("Module");
      w.Integer("mod_Nr", m.mod_nr);
      w.Vector("position", m.position);
      w.Text("axis", ToString(m.axis));
      w.Open("frames");
      for (const Frame& f : m.frames) WriteFrame(w, f);
      w.Close("frames");
      WriteJoint(w, m.joint, "joint");
      w.Close("Module");
    });
    w.List("sensorModules", r.sensor_modules,
           [&](const SensorModule& sm) { WriteSensorModule(w, sm); });
    w.List("locks", r.locks, [&](const Joint& j) { WriteJoint(w, j); });
    w.Close("robot");
  }
  w.Open("scene");
  w.Text("guid", s.scene.guid);
  w.Text("height_Image", s.scene.height_image);
  w.Vector("position", s.scene.position);
  w.Text("materialName", s.scene.material_name);
  w.Number("height", s.scene.height);
  w.Number("metersPerPixel", s.scene.meters_per_pixel);
  w.Close("scene");
  w.List("sceneObjects", s.scene_objects, [&](const SceneObject& o) {
    w.Open("SceneObject");
    w.Text("guid", o.guid);
    w.Vector("size", o.size);
    w.Vector("position", o.position);
    w.Vector("rotation", o.rotation);
    w.Quat("quatRotation", o.quat_rotation);
    w.Text("materialName", o.material_name);
    w.Text("shape", ToString(o.shape));
    w.Number("mass", o.mass);
    w.Bool("isStatic", o.is_static);
    w.Close("SceneObject");
  });
  w.List("contactFrictions", s.contact_frictions,
         [&](const ContactFriction& f) {
           w.Open("ContactFriction");
           w.Text("material1", f.material1);
           w.Text("material2", f.material2);
           w.Number("restitution", f.restitution);
           w.Number("friction", f.friction);
           w.Number("youngsModulus", f.youngs_modulus);
           w.Close("ContactFriction");
         });
  if (!s.fluid_regions.empty()) {
    w.List(
        "fluidRegions", s.fluid_regions,
        [&](const FluidRegion& r) {
          w.Open("FluidRegion");
          w.Text("guid", r.guid);
          w.Text("kind", ToString(r.kind));
          w.Vector("position", r.position);
          w.Vector("size", r.size);
          w.Number("density", r.density);
          w.Number("viscosity", r.viscosity);
          w.Vector("velocity", r.velocity);
          w.Close("FluidRegion");
        },
        false);
  }
  w.Open("settings");
  w.Number("timestep", s.settings.timestep);
  w.Vector("gravity", s.settings.gravity);
  w.Close("settings");
  if (!s.loose_frames.empty()) {
    w.List(
        "frames", s.loose_frames, [&](const Frame& f) { WriteFrame(w, f); },
        false);
  }
  if (!s.loose_sensor_modules.empty()) {
    w.List("sensorModules", s.loose_sensor_modules,
           [&](const SensorModule& sm) { WriteSensorModule(w, sm); });
  }
  if (!s.loose_joints.empty()) {
    w.List(
        "joints", s.loose_joints, [&](const Joint& j) { WriteJoint(w, j); },
        false);
  }
  w.Close("Scenario");
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n" + w.Take();
}

}  // namespace

Scenario ReadScenarioString(const std::string& xml, const std::string& name,
                            const std::string& base_dir) {
  return Reader(name, base_dir).Read(xml);
}

Scenario ReadScenarioFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || fs::is_directory(path, ec)) {
    throw ScenarioError(path + ":0: Scenario: cannot open the file (" +
                        std::strerror(errno) + ")");
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  std::string dir = fs::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  return ReadScenarioString(bytes.str(), path, dir);
}

std::string WriteScenarioString(const Scenario& scenario,
                                FrameConvention frame) {
  if (frame == FrameConvention::kZUp) return Write(scenario, frame);
  Scenario converted = scenario;
  ConvertZUpToUnity(&converted);
  return Write(converted, frame);
}

void WriteScenarioFile(const Scenario& scenario, const std::string& path,
                       FrameConvention frame) {
  WriteFileAtomically(path, WriteScenarioString(scenario, frame));
}

}  // namespace mrsim

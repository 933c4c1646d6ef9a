#include "sim_core/scenario/scenario_validate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/mesh/mesh_check.h"
#include "sim_core/scenario/face_geometry.h"
#include "sim_core/scenario/scenario_schema_inl.h"
#include "sim_core/scenario/terrain.h"

namespace mrsim {

ScenarioError::ScenarioError(const std::string& file, int line,
                             std::string path, std::string message)
    : std::runtime_error(file.empty() ? fmt::format("{}: {}", path, message)
                                      : fmt::format("{}:{}: {}: {}", file, line,
                                                    path, message)),
      path_(std::move(path)),
      message_(std::move(message)),
      line_(line) {}

int ScenarioSource::LineOf(const std::string& path) const {
  std::string p = path;
  while (!p.empty()) {
    auto it = lines.find(p);
    if (it != lines.end()) return it->second;
    const size_t slash = p.rfind('/');
    if (slash == std::string::npos) break;
    p.erase(slash);
  }
  return 0;
}

namespace {

namespace fs = std::filesystem;

// Mesh files are hostile input: larger ones are refused before anything
// (this check or MuJoCo's reader) reads them.
constexpr std::uintmax_t kMaxMeshFileBytes = 64u << 20;

std::string Lower(std::string s) {
  for (char& c : s) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return s;
}

// Which parts a joint may name.
enum class JointScope {
  kRobotBodies,  // a robot's hinge or lock: its frames and sensor modules
  kSensorLock,   // a sensor's lock: any part of its robot, sensors too
  kLooseBodies,  // a loose joint: loose frames and sensor modules
  kLooseSensorLock,
};

struct JointUse {
  const Joint* joint;
  std::string path;
  int robot;  // -1: loose parts
  JointScope scope;
};

class Validator {
 public:
  // `warnings`: where what runs but is likely not meant goes; null: it
  // is not looked for.
  Validator(const Scenario& s, const ScenarioSource* source,
            std::vector<ScenarioWarning>* warnings = nullptr)
      : s_(s), source_(source), warnings_(warnings) {}

  void Run() {
    path_ = "Scenario";
    schema::Describe(*this, const_cast<Scenario&>(s_));
    CheckJointEnds();
    for (size_t r = 0; r < s_.robots.size(); ++r)
      CheckTree(static_cast<int>(r));
    CheckTree(-1);
  }

  // Visitor interface (scenario_schema_inl.h).
  template <typename T>
  void Field(const FieldInfo& info, T& value) {
    const std::string problem = FieldRef(info, &value).Check();
    if (!problem.empty()) Fail(path_ + "/" + info.xml, problem);
  }
  template <typename P>
  void Child(const ChildInfo& info, P& part) {
    Enter(path_ + "/" + info.xml, part);
  }
  template <typename P>
  void Optional(const ChildInfo& info, std::optional<P>& part) {
    if (part) Enter(path_ + "/" + info.xml, *part, info.locks);
  }
  template <typename P, size_t N>
  void Array(const ChildInfo& info, std::array<P, N>& parts) {
    for (size_t i = 0; i < N; ++i) Enter(ItemPath(info, i), parts[i]);
  }
  template <typename P>
  void List(const ChildInfo& info, std::vector<P>& parts) {
    for (size_t i = 0; i < parts.size(); ++i) {
      if (static_cast<int>(i) == info.max_items) {
        Fail(ItemPath(info, i), ListLimitMessage(info));
      }
      Enter(ItemPath(info, i), parts[i], info.locks);
    }
  }
  void Unsupported(const ChildInfo&) {}

 private:
  std::string ItemPath(const ChildInfo& info, size_t i) const {
    if (*info.item) {
      return fmt::format("{}/{}/{}[{}]", path_, info.xml, info.item, i + 1);
    }
    return fmt::format("{}/{}[{}]", path_, info.xml, i + 1);
  }

  template <typename P>
  void Enter(const std::string& path, P& part, bool lock = false) {
    const std::string saved = path_;
    path_ = path;
    Before(part);
    schema::Describe(*this, part);
    After(part, lock);
    path_ = saved;
  }

  void Warn(const std::string& path, const std::string& what) const {
    const ScenarioError as_error =
        source_ ? ScenarioError(source_->file, source_->LineOf(path), path,
                                "warning: " + what)
                : ScenarioError("", 0, path, "warning: " + what);
    warnings_->push_back({path, what, as_error.what()});
  }

  [[noreturn]] void Fail(const std::string& path,
                         const std::string& what) const {
    if (source_) {
      throw ScenarioError(source_->file, source_->LineOf(path), path, what);
    }
    throw ScenarioError("", 0, path, what);
  }

  // "line 12, Scenario/..." or just the path for a scenario in memory.
  std::string Where(const std::string& path) const {
    if (source_) return fmt::format("line {}, {}", source_->LineOf(path), path);
    return path;
  }

  void AddGuid(const std::string& guid, bool body) {
    const std::string path = path_ + "/guid";
    auto [it, inserted] = guids_.emplace(guid, path);
    if (!inserted) {
      Fail(path, fmt::format("duplicate guid '{}' (first used at {})", guid,
                             Where(it->second)));
    }
    if (body) bodies_[robot_].push_back(guid);
  }

  void Before(const Robot& r) {
    robot_ = static_cast<int>(&r - s_.robots.data());
    module_numbers_.clear();
    const std::string name = RobotName(s_, robot_);
    const bool ok = std::all_of(name.begin(), name.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' ||
             ch == '-' || ch == '.';
    });
    if (!ok) {
      Fail(path_ + "/name",
           "expected a robot name of letters, digits, '_', '-' or '.', got "
           "'" +
               name + "'");
    }
    if (name == kSceneOwnerName || name == kLooseOwnerName) {
      Fail(
          path_ + "/name",
          fmt::format(
              "'{}' names the scenario's {} (their MuJoCo bodies and "
              "their cameras' channel), not a robot: choose another "
              "robot name",
              name, name == kSceneOwnerName ? "scene objects" : "loose parts"));
    }
    auto [it, inserted] = robot_names_.emplace(name, path_ + "/name");
    if (!inserted) {
      Fail(path_ + "/name",
           fmt::format("duplicate robot name '{}' (first at {}); robot names "
                       "must be unique",
                       name, Where(it->second)));
    }
    if (r.modules.empty() && r.sensor_modules.empty()) {
      Fail(path_ + "/modules",
           "expected at least one <Module> or "
           "<SensorModule>");
    }
  }
  void After(const Robot&, bool) { robot_ = -1; }

  void Before(const Module& m) {
    auto [it, inserted] = module_numbers_.emplace(m.mod_nr, path_ + "/mod_Nr");
    if (!inserted) {
      Fail(path_ + "/mod_Nr", fmt::format("duplicate mod_Nr {} (first at {})",
                                          m.mod_nr, Where(it->second)));
    }
  }
  void After(const Module& m, bool) {
    if (m.joint.type != JointType::kHinge) {
      Fail(path_ + "/joint/type", "a module's joint must be of type Hinge");
    }
  }

  void Before(const Frame&) {}
  void After(const Frame& f, bool) {
    AddGuid(f.guid, true);
    if (f.is_mesh()) CheckMesh(f);
    if (robot_ >= 0 && !f.is_mesh()) {
      CheckAboveTheGround(f.position, f.quat_rotation, f.scale,
                          path_ + "/position", "");
    }
  }

  void Before(const Joint&) {}
  void After(const Joint& j, bool lock) {
    // The original's all-zero GUID on a lock is a placeholder: such locks
    // are named by their place (lock<k>), so it may repeat.
    const bool placeholder =
        !j.guid.empty() && j.guid.find_first_not_of("0-") == std::string::npos;
    if (!placeholder) AddGuid(j.guid, false);
    if (j.lower_range_limit > j.upper_range_limit) {
      Fail(path_ + "/lowerRangeLimit",
           fmt::format("lower limit {} is above the upper limit {}",
                       j.lower_range_limit, j.upper_range_limit));
    }
    if (j.type == JointType::kHinge && !(j.max_vel > 0)) {
      Fail(path_ + "/max_vel",
           fmt::format("expected a positive value for a hinge, got {}",
                       j.max_vel));
    }
    if (j.left_frame_guid == j.right_frame_guid) {
      Fail(path_ + "/rightFrameGuid",
           "a joint must join two different parts, both ends are '" +
               j.left_frame_guid + "'");
    }
    const bool sensor_lock = lock && in_sensor_module_;
    if (j.servo) {
      // Only a loose hinge chooses: a module's hinge always has a servo,
      // a lock never turns. A flag that would do nothing is refused.
      if (robot_ >= 0 || lock || in_sensor_module_) {
        Fail(path_ + "/servo",
             "only a loose hinge (Scenario/joints/Joint) takes <servo>; a "
             "module's hinge always has a servo and a lock never turns");
      }
      if (j.type != JointType::kHinge) {
        Fail(path_ + "/servo",
             "a Lock does not turn, so it takes no servo (set <type> to "
             "Hinge, or leave <servo> out)");
      }
    }
    JointScope scope;
    if (robot_ >= 0) {
      scope = sensor_lock ? JointScope::kSensorLock : JointScope::kRobotBodies;
    } else {
      scope =
          sensor_lock ? JointScope::kLooseSensorLock : JointScope::kLooseBodies;
    }
    joints_.push_back({&j, path_, robot_, scope});
  }

  void Before(const SensorModule& sm) {
    in_sensor_module_ = true;
    sensor_module_ = &sm;
  }
  void After(const SensorModule& sm, bool) {
    in_sensor_module_ = false;
    sensor_module_ = nullptr;
    AddGuid(sm.guid, true);
    if (robot_ < 0) return;
    CheckAboveTheGround(sm.position, sm.quat_rotation, sm.size,
                        path_ + "/position", "");
    if (sm.force_sensor && sm.force_sensor->sensor_position >= 0 &&
        sm.force_sensor->sensor_position <= 3) {
      const PlatePose plate = ForcePlatePose(sm);
      const Eigen::Quaterniond q = sm.quat_rotation.normalized();
      CheckAboveTheGround(sm.position + q * plate.position, q * plate.rotation,
                          sm.force_sensor->size, path_ + "/position",
                          "its force plate (which the physics puts outside "
                          "the module, on face " +
                              std::to_string(sm.force_sensor->sensor_position) +
                              ") ");
    }
    for (const auto& [field, nr] :
         {std::make_pair("leftMod_Nr", sm.left_mod_nr),
          std::make_pair("rightMod_Nr", sm.right_mod_nr)}) {
      if (nr != -1 && !module_numbers_.count(nr)) {
        Fail(path_ + "/" + field,
             fmt::format("no module with mod_Nr {} in robot '{}' (use -1 for "
                         "the chain end)",
                         nr, RobotName(s_, robot_)));
      }
    }
  }

  void Before(const ForceSensor&) {}
  // Sensors are part of their sensor module's body; only their own locks
  // (which the builder does not need) may name them, so their guids are
  // optional and need not be unique.
  void After(const ForceSensor& f, bool) { sensors_[robot_].insert(f.guid); }
  void Before(const DistanceSensor&) {}
  void After(const DistanceSensor& d, bool) {
    sensors_[robot_].insert(d.guid);
    if (warnings_ != nullptr && robot_ >= 0 && sensor_module_ != nullptr) {
      Eigen::Vector3d dir = d.ray_direction;
      if (!(dir.norm() > 0) || !dir.allFinite()) {
        if (d.sensor_position >= 0 && d.sensor_position <= 5) {
          dir = SensorFaceNormal(d.sensor_position);
        }
      }
      CheckViewLeavesClearOfTheRobot(*sensor_module_, d.sensor_position, dir,
                                     false);
    }
  }
  void Before(const Camera&) {}
  void After(const Camera& c, bool) {
    if (!(c.far_clip > c.near_clip)) {
      Fail(path_ + "/far",
           fmt::format("far ({} m) must be beyond near ({} m): the camera "
                       "would draw nothing",
                       c.far_clip, c.near_clip));
    }
    // A robot's sensor module or a loose one (looking into the loose
    // parts beside it); a scene object's camera sits on the box around
    // it, so it never looks into its own part.
    if (warnings_ != nullptr && sensor_module_ != nullptr &&
        c.sensor_position >= 0 && c.sensor_position <= 5) {
      CheckViewLeavesClearOfTheRobot(*sensor_module_, c.sensor_position,
                                     SensorFaceNormal(c.sensor_position), true);
    }
  }

  // Parts with no rules beyond their fields' limits (an IMU: noise >= 0,
  // bounded biases), which Field checks.
  template <typename P>
  void Before(const P&) {}
  template <typename P>
  void After(const P&, bool) {}

  void Before(const Scene&) {}
  void After(const Scene& scene, bool) {
    if (!scene.guid.empty()) AddGuid(scene.guid, false);
    if (scene.height_image.empty()) return;
    // The physics decodes the image the same way, so what validates loads.
    try {
      LoadTerrainImage(scene, s_.base_dir);
    } catch (const std::exception& e) {
      Fail(path_ + "/height_Image",
           std::string("cannot read the height image: ") + e.what());
    }
  }

  // What the chosen controller needs is there: a script to run, a name
  // to wait for.
  void After(const RunSettings& run, bool) {
    if (run.controller == ControllerKind::kLua && run.lua_script.empty()) {
      Fail(path_ + "/luaScript",
           "expected the Lua script's source for controller lua");
    }
    if (run.controller == ControllerKind::kExternal &&
        !ValidControllerName(run.external_name)) {
      Fail(path_ + "/externalName",
           "expected 1-64 letters, digits, '-', '_' or '.', starting with a "
           "letter or digit, for controller external, got '" +
               run.external_name + "'");
    }
  }

  // One source of genes, as mrsim-opt's --genes and --genome exclude each
  // other; what the words mean the optimizer checks (opt_file_setup.h).
  void After(const OptimizationSettings& o, bool) {
    if (!o.genes.empty() && !o.genome.empty()) {
      Fail(path_ + "/genes",
           "expected genes or genome, not both (a built-in gene set, or "
           "the genes written out)");
    }
  }

  void Before(const SceneObject&) {}
  void After(const SceneObject& o, bool) {
    AddGuid(o.guid, false);
    if (!o.is_static && !(o.mass > 0)) {
      Fail(path_ + "/mass",
           fmt::format("expected a positive value, got {} (only a static "
                       "object may have mass 0)",
                       o.mass));
    }
  }

  void Before(const ContactFriction&) {}
  void After(const ContactFriction& f, bool) {
    auto key = std::minmax(f.material1, f.material2);
    auto [it, inserted] =
        pairs_.emplace(std::make_pair(key.first, key.second), path_);
    if (!inserted) {
      Fail(path_, fmt::format("second ContactFriction for materials '{}'/'{}' "
                              "(first at {})",
                              f.material1, f.material2, Where(it->second)));
    }
  }

  void Before(const FluidRegion&) {}
  void After(const FluidRegion& r, bool) {
    if (!r.guid.empty()) AddGuid(r.guid, false);
  }
  void Before(const SimulationSettings&) {}
  void After(const SimulationSettings&, bool) {}
  void Before(const Scenario&) {}
  void After(const Scenario&, bool) {}

  void CheckMesh(const Frame& frame) {
    const std::string path = path_ + "/shape";
    const std::string ext = Lower(fs::path(frame.shape).extension().string());
    if (ext != ".obj" && ext != ".stl") {
      Fail(path, "expected Box or a mesh file ending in .obj or .stl, got '" +
                     frame.shape + "'");
    }
    // A mesh carried inside the scenario (the optimiser's payload, a design
    // saved with its assets) names no file: its bytes are checked alike.
    if (IsEmbeddedMesh(frame.shape)) {
      EmbeddedMesh mesh;
      try {
        mesh = DecodeEmbeddedMesh(frame.shape);
      } catch (const std::exception& e) {
        Fail(path, std::string("embedded mesh: ") + e.what());
      }
      if (mesh.bytes.size() > kMaxMeshFileBytes) {
        Fail(path, "embedded mesh '" + mesh.file_name + "' is larger than " +
                       std::to_string(kMaxMeshFileBytes >> 20) + " MB");
      }
      CheckMeshBytes(path, "embedded mesh '" + mesh.file_name + "'", mesh.bytes,
                     mesh.file_name, frame.scale);
      return;
    }
    fs::path p(frame.shape);
    if (p.is_relative() && !s_.base_dir.empty()) p = fs::path(s_.base_dir) / p;
    const std::string resolved = p.string();
    std::ifstream in(resolved, std::ios::binary);
    std::error_code ec;
    if (!in || !fs::is_regular_file(resolved, ec)) {
      Fail(path, "cannot read mesh file '" + resolved + "'");
    }
    // A mesh file is hostile input: its size is checked before anything
    // reads it, here or in MuJoCo.
    const std::uintmax_t size = fs::file_size(resolved, ec);
    if (ec || size > kMaxMeshFileBytes) {
      Fail(path, "mesh file '" + resolved + "' is larger than " +
                     std::to_string(kMaxMeshFileBytes >> 20) + " MB");
    }
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                           std::istreambuf_iterator<char>());
    CheckMeshBytes(path, "mesh file '" + resolved + "'", bytes, frame.shape,
                   frame.scale);
  }

  // The cheap shape of an OBJ or STL first (a clear word on what a file of
  // the wrong kind lacks), then MuJoCo's own reader at the frame's scale.
  void CheckMeshBytes(const std::string& path, const std::string& what,
                      const std::vector<unsigned char>& data,
                      const std::string& file_name,
                      const Eigen::Vector3d& scale) {
    const std::string ext = Lower(fs::path(file_name).extension().string());
    const std::string bytes(data.begin(), data.end());
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
    }
    if (!ok && ext == ".stl" && bytes.rfind("solid", 0) == 0 &&
        bytes.find("facet") != std::string::npos) {
      Fail(path, what +
                     " is an ASCII STL: MuJoCo reads binary STL only (export "
                     "it as binary STL)");
    }
    if (!ok) {
      Fail(path, what + " is not a valid " +
                     (ext == ".obj" ? "OBJ (needs v and f lines)"
                                    : "binary STL (80-byte header, triangle "
                                      "count, 50 bytes a triangle)"));
    }
    try {
      CheckMeshReadable(data, file_name, scale);
    } catch (const std::exception& e) {
      Fail(path, what + ": MuJoCo cannot read it: " + e.what());
    }
  }

  // Joints name parts the simulator can join (mjcf_builder.cc): a robot's
  // hinges and locks its own frames and sensor modules, loose joints loose
  // frames and sensor modules; a sensor's lock may name its sensors too.
  void CheckJointEnds() const {
    std::set<std::string> everywhere;
    for (const auto& [robot, names] : bodies_) {
      everywhere.insert(names.begin(), names.end());
    }
    for (const auto& [robot, names] : sensors_) {
      everywhere.insert(names.begin(), names.end());
    }
    for (const JointUse& use : joints_) {
      auto bodies_it = bodies_.find(use.robot);
      std::set<std::string> allowed;
      if (bodies_it != bodies_.end()) {
        allowed.insert(bodies_it->second.begin(), bodies_it->second.end());
      }
      const bool sensors_ok = use.scope == JointScope::kSensorLock ||
                              use.scope == JointScope::kLooseSensorLock;
      auto sensors_it = sensors_.find(use.robot);
      if (sensors_ok && sensors_it != sensors_.end()) {
        allowed.insert(sensors_it->second.begin(), sensors_it->second.end());
      }
      for (const char* end : {"leftFrameGuid", "rightFrameGuid"}) {
        const std::string& guid = std::string(end) == "leftFrameGuid"
                                      ? use.joint->left_frame_guid
                                      : use.joint->right_frame_guid;
        if (allowed.count(guid)) continue;
        const std::string what = sensors_ok ? "frame, sensor module or sensor"
                                            : "frame or sensor module";
        std::string hint;
        if (everywhere.count(guid) || guids_.count(guid)) {
          hint = use.robot >= 0
                     ? " (it is not a part this joint can join; joints of a "
                       "robot join only its own frames and sensor modules)"
                     : " (it is not a part this joint can join; loose joints "
                       "join loose frames and sensor modules)";
        }
        const std::string where =
            use.robot >= 0
                ? fmt::format(" in robot '{}'", RobotName(s_, use.robot))
                : " among the loose parts";
        Fail(use.path + "/" + end,
             fmt::format("no {} with guid '{}'{}{}", what, guid, where, hint));
      }
    }
  }

  // As the builder joins parts (mjcf_builder.cc): hinges first, each must
  // join two parts not yet joined (MuJoCo joints live in a tree); then
  // locks, and sensor modules no joint names are locked to their
  // neighbouring modules. Every part of a robot must end up joined.
  void CheckTree(int robot) const {
    auto bodies_it = bodies_.find(robot);
    if (bodies_it == bodies_.end()) return;
    const std::vector<std::string>& nodes = bodies_it->second;
    std::map<std::string, std::string> parent;
    for (const std::string& n : nodes) parent[n] = n;
    std::function<std::string(const std::string&)> root =
        [&](const std::string& x) -> std::string {
      const std::string& p = parent.at(x);
      return p == x ? x : parent[x] = root(p);
    };
    std::vector<const JointUse*> edges;
    std::set<std::string> named;
    for (const JointUse& use : joints_) {
      if (use.robot != robot || (use.scope != JointScope::kRobotBodies &&
                                 use.scope != JointScope::kLooseBodies)) {
        continue;
      }
      edges.push_back(&use);
      named.insert(use.joint->left_frame_guid);
      named.insert(use.joint->right_frame_guid);
    }
    for (int pass = 0; pass < 2; ++pass) {
      for (const JointUse* use : edges) {
        const bool hinge = use->joint->type == JointType::kHinge;
        if (hinge != (pass == 0)) continue;
        const std::string a = root(use->joint->left_frame_guid);
        const std::string b = root(use->joint->right_frame_guid);
        if (a == b && hinge) {
          Fail(use->path,
               fmt::format("hinge '{}' closes a loop of hinges and locks; "
                           "hinges that form a closed loop are not supported",
                           use->joint->guid));
        }
        parent[a] = b;
      }
    }
    if (robot < 0) return;
    const Robot& r = s_.robots[robot];
    for (const SensorModule& sm : r.sensor_modules) {
      if (named.count(sm.guid)) continue;
      for (const Module& m : r.modules) {
        if (m.mod_nr == sm.left_mod_nr || m.mod_nr == sm.right_mod_nr) {
          parent[root(m.frames[0].guid)] = root(sm.guid);
          parent[root(m.frames[1].guid)] = root(sm.guid);
        }
      }
    }
    const std::string first = root(nodes.front());
    for (const std::string& n : nodes) {
      if (root(n) != first) {
        Fail(guids_.at(n),
             fmt::format("part '{}' is not joined to the rest of robot '{}' "
                         "(expected a hinge or a lock in <locks> linking it)",
                         n, RobotName(s_, robot)));
      }
    }
  }

  // A robot part that starts inside the ground (the plane, or the height
  // field's base) is thrown out of it at the first step: the robot jumps
  // or flies off before any controller acts. Checked for boxes at the pose
  // in the file, 1 mm of slack.
  void CheckAboveTheGround(const Eigen::Vector3d& centre,
                           const Eigen::Quaterniond& rotation,
                           const Eigen::Vector3d& size, const std::string& path,
                           const std::string& what) const {
    if (!centre.allFinite() || !size.allFinite()) return;
    const Eigen::Matrix3d r = rotation.normalized().toRotationMatrix();
    // Half the box's extent along world z.
    const double reach =
        (r.row(2).cwiseAbs().transpose().array() * (size / 2).array().abs())
            .sum();
    const double ground = s_.scene.position.z();
    const double depth = ground - (centre.z() - reach);
    if (!(depth > kGroundSlack)) return;
    Fail(path, fmt::format("{}starts {:.1f} mm below the ground (its lowest "
                           "point at z = {:.4g} m, the ground at z = {:.4g} "
                           "m), so the physics would throw the robot out of "
                           "the ground at the first step; raise the robot "
                           "(every part's z) by at least {:.1f} mm",
                           what, depth * 1e3, centre.z() - reach, ground,
                           depth * 1e3));
  }
  static constexpr double kGroundSlack = 1e-3;

  // A ray that meets another of the robot's boxes where it leaves its own
  // module hits it at once and reads about 0 for the whole run: a face
  // turned to a neighbour (the front face of a sensor module behind module
  // 0, say), or a ray looking back through its module into the next.
  // Checked at the pose in the file, against box frames and sensor modules.
  // A warning, not a refusal: the design still runs (the original MRSim
  // ran such files, e.g. its thesis's Appendix F, whose frames of
  // <scale>10</scale> enclose the sensor module in front of them).
  // A camera looking out of such a face sees only that neighbour.
  void CheckViewLeavesClearOfTheRobot(const SensorModule& sm, int face,
                                      const Eigen::Vector3d& dir, bool camera) {
    // Faces and sizes out of range are told on their own.
    if (face < 0 || face > 5) return;
    if (!(sm.size.minCoeff() > 0) || !sm.position.allFinite()) return;
    if (!(dir.norm() > 0) || !dir.allFinite()) return;
    const Eigen::Vector3d n = SensorFaceNormal(face);
    // Where the ray leaves its own module (which it skips): at once through
    // its face, or, looking back through the module, out of another face.
    const Eigen::Vector3d half = sm.size / 2;
    const Eigen::Vector3d from = n * std::abs(n.dot(half));
    const Eigen::Vector3d along = dir.normalized();
    double leave = INFINITY;
    for (int i = 0; i < 3; ++i) {
      if (std::abs(along[i]) < 1e-12) continue;
      const double wall = along[i] > 0 ? half[i] : -half[i];
      leave = std::min(leave, (wall - from[i]) / along[i]);
    }
    if (!std::isfinite(leave)) leave = 0;
    // 1 mm beyond, as the physics casts it.
    const Eigen::Vector3d probe =
        sm.position + sm.quat_rotation.normalized() *
                          (from + (std::max(leave, 0.0) + 1e-3) * along);
    const auto inside = [&probe](const Eigen::Vector3d& centre,
                                 const Eigen::Quaterniond& rotation,
                                 const Eigen::Vector3d& size) {
      const Eigen::Vector3d local =
          rotation.normalized().conjugate() * (probe - centre);
      return (local.cwiseAbs().array() < size.array() / 2).all();
    };
    std::string hit;
    const auto frame_in_view = [&](const Frame& f) {
      if (!f.is_mesh() && inside(f.position, f.quat_rotation, f.scale)) {
        hit = f.guid;
      }
    };
    if (robot_ >= 0) {
      for (const Module& m : s_.robots[robot_].modules) {
        for (const Frame& f : m.frames) frame_in_view(f);
      }
    } else {
      for (const Frame& f : s_.loose_frames) frame_in_view(f);
    }
    for (const SensorModule& other : robot_ >= 0
                                         ? s_.robots[robot_].sensor_modules
                                         : s_.loose_sensor_modules) {
      if (&other != &sm &&
          inside(other.position, other.quat_rotation, other.size)) {
        hit = other.guid;
      }
    }
    if (hit.empty()) return;
    const char* ahead = face == 4 ? " (for a sensor looking ahead: a sensor "
                                    "module in front of module 0)"
                                  : "";
    if (camera) {
      Warn(path_ + "/sensorPosition",
           fmt::format("the camera on face {} ({}) looks straight into '{}', "
                       "so it would see only {}; put it on a face that looks "
                       "out{}",
                       face, kSensorFaceNames[face], hit,
                       robot_ >= 0 ? "that part of its own robot"
                                   : "that loose part beside it",
                       ahead));
      return;
    }
    Warn(path_ + "/sensorPosition",
         fmt::format("the ray of face {} ({}) runs into '{}' as it leaves its "
                     "sensor module, so it would read about 0 the whole run; "
                     "put the sensor on a face that looks out{}",
                     face, kSensorFaceNames[face], hit, ahead));
  }

  const Scenario& s_;
  const ScenarioSource* source_;
  std::vector<ScenarioWarning>* warnings_;
  std::string path_;
  int robot_ = -1;  // index of the robot being walked; -1: loose parts
  const SensorModule* sensor_module_ = nullptr;  // the one being walked
  bool in_sensor_module_ = false;
  std::map<std::string, std::string> guids_;  // guid -> path of its <guid>
  std::map<std::string, std::string> robot_names_;
  std::map<int, std::string> module_numbers_;
  std::map<std::pair<std::string, std::string>, std::string> pairs_;
  // Frames and sensor modules (what the builder makes bodies of) and
  // sensors, per robot index; -1 for loose parts.
  std::map<int, std::vector<std::string>> bodies_;
  std::map<int, std::set<std::string>> sensors_;
  std::vector<JointUse> joints_;
};

}  // namespace

void ValidateScenario(const Scenario& scenario, const ScenarioSource* source) {
  Validator(scenario, source).Run();
}

std::vector<ScenarioWarning> ScenarioWarnings(const Scenario& scenario,
                                              const ScenarioSource* source) {
  std::vector<ScenarioWarning> warnings;
  Validator(scenario, source, &warnings).Run();
  return warnings;
}

}  // namespace mrsim

#include "studio/design/design.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "sim_core/export/frame_mesh.h"
#include "sim_core/scenario/embed_assets.h"
#include "sim_core/scenario/face_geometry.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/scenario/sensor_face.h"
#include "studio/design/chain_edit.h"
#include "studio/design/ground_move.h"
#include "studio/design/inspector_fields.h"
#include "studio/design/schema.h"

namespace mrsim::studio {
namespace {

constexpr size_t kMaxUndo = 500;

bool IsChainPart(const Selection& s) {
  return s.kind == SelectionKind::kModule ||
         s.kind == SelectionKind::kSensorModule;
}

// Position of the selected chain part in ChainOrder, or -1.
int SlotOf(const std::vector<ChainSlot>& slots, const Selection& sel) {
  for (size_t i = 0; i < slots.size(); ++i) {
    if (slots[i].sensor == (sel.kind == SelectionKind::kSensorModule) &&
        slots[i].source == sel.index) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

// The selection of the part at `slot` once `slots` are laid out.
Selection SelectionAt(const std::vector<ChainSlot>& slots, int robot,
                      int slot) {
  int modules = 0, sensors = 0;
  for (int i = 0; i < slot; ++i) (slots[i].sensor ? sensors : modules)++;
  return {slots[slot].sensor ? SelectionKind::kSensorModule
                             : SelectionKind::kModule,
          robot, slots[slot].sensor ? sensors : modules};
}

// x of the front face of the robot's frontmost part.
double FrontOf(const Robot& robot) {
  double front = -INFINITY;
  for (const Module& m : robot.modules) {
    for (const Frame& f : m.frames) {
      front = std::max(front, f.position.x() + f.scale.x() / 2);
    }
  }
  for (const SensorModule& sm : robot.sensor_modules) {
    front = std::max(front, sm.position.x() + sm.size.x() / 2);
    for (const DistanceSensor& d : sm.distance_sensors) {
      front = std::max(front, d.position.x() + d.size.x() / 2);
    }
  }
  return std::isfinite(front) ? front : 0.0;
}

std::string UniqueGuid(const Scenario& s, const std::string& base) {
  auto used = [&](const std::string& g) {
    for (const SceneObject& o : s.scene_objects) {
      if (o.guid == g) return true;
    }
    for (const FluidRegion& f : s.fluid_regions) {
      if (f.guid == g) return true;
    }
    return false;
  };
  if (!used(base)) return base;
  for (int i = 2;; ++i) {
    const std::string g = base + std::to_string(i);
    if (!used(g)) return g;
  }
}

// Relayout for a robot that may have been turned on the ground: laid out
// facing +x about module 0's hinge, then turned back, so reordering a turned
// robot keeps its heading. A robot facing +x is laid out as before.
Robot RelayoutFacing(const Robot& old, const std::vector<ChainSlot>& slots,
                     const ChainOptions& options, const std::string& base_dir) {
  const double heading = RobotHeading(old);
  if (heading == 0.0) return Relayout(old, slots, options, base_dir);
  const Eigen::Vector3d pivot = old.modules[0].position;
  Robot straight = old;
  TransformRobot(&straight, GroundTransform(pivot, {{0, 0}, -heading}));
  Robot out = Relayout(straight, slots, options, base_dir);
  TransformRobot(&out, GroundTransform(pivot, {{0, 0}, heading}));
  return out;
}

// A ray put on a face turned to a neighbour reads about 0 the whole run.
// Files holding one load with a warning (ScenarioWarnings); the designer
// does not add one. Throws DesignError with the warning that `after`
// gained over `before`; an `after` the validator refuses is left to
// Commit, which says why.
void RefuseUselessRay(const Scenario& before, const Scenario& after) {
  std::vector<ScenarioWarning> now;
  try {
    now = ScenarioWarnings(after);
  } catch (const ScenarioError&) {
    return;
  }
  std::set<std::string> had;
  for (const ScenarioWarning& w : ScenarioWarnings(before)) had.insert(w.path);
  for (const ScenarioWarning& w : now) {
    if (!had.count(w.path)) throw DesignError(w.message);
  }
}

}  // namespace

Scenario EmptyScenario() {
  Scenario s;
  s.scene.guid = "scene";
  s.scene.material_name = "ground";
  return s;
}

Scenario MakeTemplateScenario(const TemplateOptions& options) {
  try {
    return MakeChainScenario(options);
  } catch (const std::invalid_argument& e) {
    throw DesignError(e.what());
  }
}

Design::Design() : scenario_(EmptyScenario()) {
  saved_text_ = WriteScenarioString(scenario_);
}

Design Design::Open(const std::string& path) {
  Design design;
  design.path_ = path;
  const bool exists = std::filesystem::exists(path);
  if (exists && IsOriginalMrsimFile(path)) {
    // The original's own file: converted on open, saved beside it in the
    // native frame, so the original stays as it was.
    design.scenario_ = ReadScenarioFile(path, kOriginalMrsimReadOptions);
    const std::filesystem::path p(path);
    design.path_ =
        (p.parent_path() / (p.stem().string() + ".native.xml")).string();
    design.dirty_ = true;  // saved_text_ stays empty: nothing native yet
    design.note_ =
        "an original MRSim file (Unity, cm), converted: Save "
        "writes " +
        std::filesystem::path(design.path_).filename().string();
  } else if (exists) {
    design.scenario_ = ReadScenarioFile(path);
    design.saved_text_ = WriteScenarioString(design.scenario_);
  } else {
    const auto dir = std::filesystem::absolute(path).parent_path();
    design.scenario_.base_dir = dir.string();
  }
  if (!design.scenario_.robots.empty() &&
      !design.scenario_.robots[0].modules.empty()) {
    design.selection_ = {SelectionKind::kModule, 0, 0};
  }
  return design;
}

void Design::Select(const Selection& selection) {
  Scenario copy = scenario_;
  const bool valid = selection.kind == SelectionKind::kNone ||
                     !InspectorFields(copy, selection).empty();
  selection_ = valid ? selection : Selection{};
}

int Design::TargetRobot() const {
  if (IsChainPart(selection_) || selection_.kind == SelectionKind::kRobot ||
      selection_.kind == SelectionKind::kLock) {
    return selection_.robot;
  }
  return scenario_.robots.empty() ? -1 : 0;
}

void Design::Commit(Scenario next, const Selection& selection) {
  try {
    ValidateScenario(next);
  } catch (const ScenarioError& e) {
    // What is wrong, without the XML path: the student clicked the part.
    throw DesignError(e.message().empty() ? e.what() : e.message());
  } catch (const std::exception& e) {
    throw DesignError(e.what());
  }
  undo_.push_back({std::move(scenario_), selection_});
  if (undo_.size() > kMaxUndo) undo_.erase(undo_.begin());
  redo_.clear();
  scenario_ = std::move(next);
  selection_ = selection;
  Changed();
}

void Design::Changed() {
  ++revision_;
  dirty_ = WriteScenarioString(scenario_) != saved_text_;
}

void Design::AddPart(NextPart part, Where where) {
  int r = TargetRobot();
  int at = 0;
  if (r < 0) {
    r = 0;
  } else {
    const std::vector<ChainSlot> slots = ChainOrder(scenario_.robots[r]);
    at = where == Where::kFront ? 0 : static_cast<int>(slots.size());
    if (where == Where::kAfterSelection && IsChainPart(selection_) &&
        selection_.robot == r) {
      const int selected = SlotOf(slots, selection_);
      if (selected >= 0) at = selected + 1;
    }
  }
  InsertPart(part, r, at);
}

void Design::InsertPart(NextPart part, int robot, int at) {
  Scenario next = scenario_;
  if (next.robots.empty() && robot == 0) {
    next.robots.push_back(Robot{});
    next.robots.back().name = ChainOptions().name;
  }
  if (robot < 0 || robot >= static_cast<int>(next.robots.size())) {
    throw DesignError("there is no robot " + std::to_string(robot));
  }
  const Robot& old = next.robots[robot];
  std::vector<ChainSlot> slots = ChainOrder(old);
  at = std::clamp(at, 0, static_cast<int>(slots.size()));
  ChainSlot slot;
  slot.sensor = part == NextPart::kSensorModule;
  slot.axis = part == NextPart::kYawModule ? Axis::kYaw : Axis::kPitch;
  slots.insert(slots.begin() + at, slot);
  try {
    next.robots[robot] =
        RelayoutFacing(old, slots, OptionsOf(old), scenario_.base_dir);
  } catch (const std::invalid_argument& e) {
    throw DesignError(e.what());
  }
  Commit(std::move(next), SelectionAt(slots, robot, at));
}

void Design::AddRobot() {
  if (scenario_.robots.empty()) {
    InsertPart(NextPart::kPitchModule, 0, 0);
    return;
  }
  Scenario next = scenario_;
  ChainOptions options = OptionsOf(next.robots[0]);
  options.modules = 1;
  options.sensor_after.clear();
  options.force_sensors = false;
  options.front_distance_sensor = false;
  double left = -INFINITY;
  for (const Robot& r : next.robots) {
    for (const Module& m : r.modules) left = std::max(left, m.position.y());
    for (const SensorModule& sm : r.sensor_modules)
      left = std::max(left, sm.position.y());
  }
  options.origin.y() = (std::isfinite(left) ? left : 0.0) + 0.3;
  for (int i = static_cast<int>(next.robots.size()) + 1;; ++i) {
    options.name = "robot" + std::to_string(i);
    bool used = false;
    for (const Robot& r : next.robots) used = used || r.name == options.name;
    if (!used) break;
  }
  try {
    next.robots.push_back(MakeChain(options));
  } catch (const std::invalid_argument& e) {
    throw DesignError(e.what());
  }
  const int r = static_cast<int>(next.robots.size()) - 1;
  Commit(std::move(next), {SelectionKind::kRobot, r, 0});
}

void Design::AddObject(ObjectKind kind) {
  Scenario next = scenario_;
  SceneObject o;
  const double front = next.robots.empty() ? 0.0 : FrontOf(next.robots[0]);
  const double ground = next.robots.empty() || next.robots[0].modules.empty()
                            ? 0.0
                            : OptionsOf(next.robots[0]).origin.z();
  const char* name = "box";
  switch (kind) {
    case ObjectKind::kBall:
      name = "ball";
      o.shape = PrimitiveShape::kSphere;
      o.size = Eigen::Vector3d(0.1, 0.1, 0.1);
      o.mass = 0.05;
      break;
    case ObjectKind::kBox:
      o.shape = PrimitiveShape::kBox;
      o.size = Eigen::Vector3d(0.1, 0.1, 0.1);
      o.mass = 0.2;
      break;
    case ObjectKind::kCylinder:
      name = "cylinder";
      o.shape = PrimitiveShape::kCylinder;
      o.size = Eigen::Vector3d(0.1, 0.1, 0.1);
      o.mass = 0.2;
      break;
    case ObjectKind::kCapsule:
      name = "capsule";
      o.shape = PrimitiveShape::kCapsule;
      o.size = Eigen::Vector3d(0.06, 0.06, 0.16);
      o.mass = 0.1;
      break;
    case ObjectKind::kRamp:
      name = "ramp";
      o.shape = PrimitiveShape::kBox;
      o.size = Eigen::Vector3d(0.5, 0.3, 0.02);
      o.mass = 1.0;
      o.is_static = true;
      // Rises towards +x, the way the robot crawls.
      o.rotation = Eigen::Vector3d(0, -10, 0);
      o.quat_rotation =
          Eigen::AngleAxisd(-10 * M_PI / 180, Eigen::Vector3d::UnitY());
      break;
  }
  o.guid = UniqueGuid(next, name);
  const double gap =
      0.3 + 0.25 * static_cast<double>(next.scene_objects.size());
  const double half = kind == ObjectKind::kRamp ? 0.25 : o.size.x() / 2;
  const double height =
      kind == ObjectKind::kCapsule || kind == ObjectKind::kCylinder
          ? o.size.z() / 2 + (kind == ObjectKind::kCapsule ? o.size.x() / 2 : 0)
          : o.size.z() / 2;
  o.position = Eigen::Vector3d(
      front + gap + half, 0,
      ground + (kind == ObjectKind::kRamp ? 0.25 * std::sin(10 * M_PI / 180)
                                          : height));
  if (!next.robots.empty()) {
    o.position.y() = OptionsOf(next.robots[0]).origin.y();
  }
  next.scene_objects.push_back(o);
  Commit(std::move(next), {SelectionKind::kSceneObject, 0,
                           static_cast<int>(next.scene_objects.size()) - 1});
}

void Design::AddFluid(FluidKind kind) {
  Scenario next = scenario_;
  FluidRegion f;
  f.kind = kind;
  f.guid = UniqueGuid(next, kind == FluidKind::kWater ? "water" : "air");
  const double front = next.robots.empty() ? 0.0 : FrontOf(next.robots[0]);
  if (kind == FluidKind::kWater) {
    f.size = Eigen::Vector3d(1.0, 1.0, 0.2);
    f.position = Eigen::Vector3d(front + 0.8, 0, 0.1);
  } else {
    f.density = FluidRegion::kAirDensity;
    f.viscosity = FluidRegion::kAirViscosity;
    f.size = Eigen::Vector3d(2.0, 2.0, 1.0);
    f.position = Eigen::Vector3d(0, 0, 0.5);
  }
  next.fluid_regions.push_back(f);
  const int index = static_cast<int>(next.fluid_regions.size()) - 1;
  Commit(std::move(next), {SelectionKind::kFluidRegion, 0, index});
}

void Design::AddContact() {
  Scenario next = scenario_;
  ContactFriction pair;
  pair.material1 = next.robots.empty() || next.robots[0].modules.empty()
                       ? "plastic"
                       : next.robots[0].modules[0].frames[0].material_name;
  pair.material2 = next.scene.material_name;
  next.contact_frictions.push_back(pair);
  const int index = static_cast<int>(next.contact_frictions.size()) - 1;
  Commit(std::move(next), {SelectionKind::kContactFriction, 0, index});
}

void Design::RemoveSelected() {
  Scenario next = scenario_;
  const Selection sel = selection_;
  auto erase = [&](auto& list) {
    if (sel.index < 0 || sel.index >= static_cast<int>(list.size())) {
      throw DesignError("nothing selected to remove");
    }
    list.erase(list.begin() + sel.index);
    const int left = static_cast<int>(list.size());
    return left == 0
               ? Selection{}
               : Selection{sel.kind, sel.robot, std::min(sel.index, left - 1)};
  };
  Selection after;
  switch (sel.kind) {
    case SelectionKind::kModule:
    case SelectionKind::kSensorModule: {
      const Robot& old = next.robots.at(sel.robot);
      std::vector<ChainSlot> slots = ChainOrder(old);
      const int at = SlotOf(slots, sel);
      if (at < 0) throw DesignError("nothing selected to remove");
      slots.erase(slots.begin() + at);
      if (slots.empty()) {
        next.robots.erase(next.robots.begin() + sel.robot);
        break;
      }
      try {
        next.robots[sel.robot] =
            RelayoutFacing(old, slots, OptionsOf(old), scenario_.base_dir);
      } catch (const std::invalid_argument& e) {
        throw DesignError("cannot remove it: " + std::string(e.what()));
      }
      after = SelectionAt(slots, sel.robot,
                          std::min(at, static_cast<int>(slots.size()) - 1));
      break;
    }
    case SelectionKind::kSceneObject:
      after = erase(next.scene_objects);
      break;
    case SelectionKind::kFluidRegion:
      after = erase(next.fluid_regions);
      break;
    case SelectionKind::kContactFriction:
      after = erase(next.contact_frictions);
      break;
    case SelectionKind::kLock:
      DetachLock();
      return;
    case SelectionKind::kLooseJoint:
      after = erase(next.loose_joints);
      break;
    case SelectionKind::kLooseFrame:
    case SelectionKind::kLooseSensorModule: {
      const std::string guid =
          sel.kind == SelectionKind::kLooseFrame
              ? next.loose_frames.at(sel.index).guid
              : next.loose_sensor_modules.at(sel.index).guid;
      after = sel.kind == SelectionKind::kLooseFrame
                  ? erase(next.loose_frames)
                  : erase(next.loose_sensor_modules);
      // Its joints join nothing now.
      auto& joints = next.loose_joints;
      joints.erase(std::remove_if(joints.begin(), joints.end(),
                                  [&](const Joint& j) {
                                    return j.left_frame_guid == guid ||
                                           j.right_frame_guid == guid;
                                  }),
                   joints.end());
      break;
    }
    default:
      throw DesignError(
          "select a part, object, region, contact, lock or loose part to "
          "remove");
  }
  Commit(std::move(next), after);
}

namespace {

// Every guid the scenario's parts go by, so a new part's is unique.
std::set<std::string> AllGuids(const Scenario& s) {
  std::set<std::string> g;
  auto sensor_module = [&](const SensorModule& sm) {
    g.insert(sm.guid);
    for (const DistanceSensor& d : sm.distance_sensors) g.insert(d.guid);
    for (const Camera& c : sm.cameras) g.insert(c.guid);
  };
  for (const Robot& r : s.robots) {
    for (const Module& m : r.modules) {
      g.insert(m.frames[0].guid);
      g.insert(m.frames[1].guid);
      g.insert(m.joint.guid);
    }
    for (const SensorModule& sm : r.sensor_modules) sensor_module(sm);
    for (const Joint& j : r.locks) g.insert(j.guid);
  }
  for (const SceneObject& o : s.scene_objects) g.insert(o.guid);
  for (const FluidRegion& f : s.fluid_regions) g.insert(f.guid);
  for (const Frame& f : s.loose_frames) g.insert(f.guid);
  for (const Joint& j : s.loose_joints) g.insert(j.guid);
  for (const SensorModule& sm : s.loose_sensor_modules) sensor_module(sm);
  return g;
}

std::string FreshGuid(const std::set<std::string>& used,
                      const std::string& base) {
  for (int i = 0;; ++i) {
    const std::string g = base + std::to_string(i);
    if (!used.count(g)) return g;
  }
}

// The parts of `robot` a lock may join, in chain order, named in words.
std::vector<LockEnd> EndsOf(const Robot& robot) {
  std::vector<LockEnd> ends;
  for (const ChainSlot& slot : ChainOrder(robot)) {
    if (slot.sensor) {
      ends.push_back({robot.sensor_modules[slot.source].guid,
                      "S" + std::to_string(slot.source) + " sensor module"});
      continue;
    }
    const Module& m = robot.modules[slot.source];
    for (int f = 0; f < 2; ++f) {
      ends.push_back(
          {m.frames[f].guid,
           "module " + std::to_string(slot.source) + " " + FrameName(f)});
    }
  }
  return ends;
}

// Whether a loose joint joins `a` and `b` directly.
bool JoinedLoose(const Scenario& s, const std::string& a,
                 const std::string& b) {
  for (const Joint& j : s.loose_joints) {
    if ((j.left_frame_guid == a && j.right_frame_guid == b) ||
        (j.left_frame_guid == b && j.right_frame_guid == a)) {
      return true;
    }
  }
  return false;
}

// Whether a hinge or lock of `robot` joins `a` and `b` directly.
bool Joined(const Robot& robot, const std::string& a, const std::string& b) {
  auto joins = [&](const Joint& j) {
    return (j.left_frame_guid == a && j.right_frame_guid == b) ||
           (j.left_frame_guid == b && j.right_frame_guid == a);
  };
  for (const Module& m : robot.modules) {
    if (joins(m.joint)) return true;
  }
  for (const Joint& j : robot.locks) {
    if (joins(j)) return true;
  }
  return false;
}

}  // namespace

void Design::AddLoose(LoosePart part) {
  Scenario next = scenario_;
  std::set<std::string> used = AllGuids(next);
  // Beside the robots, on their ground, 0.3 m to their right (-y), each
  // new loose part a little further back than the last.
  double right = INFINITY;
  double ground = 0.0;
  double x = 0.0;
  for (const Robot& r : next.robots) {
    for (const Module& m : r.modules) right = std::min(right, m.position.y());
    for (const SensorModule& sm : r.sensor_modules) {
      right = std::min(right, sm.position.y());
    }
  }
  if (!next.robots.empty() && !next.robots[0].modules.empty()) {
    const ChainOptions options = OptionsOf(next.robots[0]);
    ground = options.origin.z();
    x = options.origin.x();
  }
  const double y = (std::isfinite(right) ? right : 0.0) - 0.3;
  x -= 0.15 * static_cast<double>(next.loose_frames.size() +
                                  next.loose_sensor_modules.size());
  Selection selected;
  auto frame_at = [&](double fx) {
    Frame f;
    f.guid = FreshGuid(used, "loose/f");
    used.insert(f.guid);
    f.position = Eigen::Vector3d(fx, y, ground + f.scale.z() / 2);
    next.loose_frames.push_back(f);
    return f.guid;
  };
  switch (part) {
    case LoosePart::kFrame:
      frame_at(x);
      selected = {SelectionKind::kLooseFrame, 0,
                  static_cast<int>(next.loose_frames.size()) - 1};
      break;
    case LoosePart::kSensorModule: {
      SensorModule sm;
      sm.guid = FreshGuid(used, "loose/s");
      sm.position = Eigen::Vector3d(x, y, ground + sm.size.z() / 2);
      next.loose_sensor_modules.push_back(sm);
      selected = {SelectionKind::kLooseSensorModule, 0,
                  static_cast<int>(next.loose_sensor_modules.size()) - 1};
      break;
    }
    case LoosePart::kHinge: {
      // Two frames touching along x, the hinge at their faces about y.
      const double half = Frame().scale.x() / 2;
      Joint j;
      j.guid = FreshGuid(used, "loose/j");
      j.type = JointType::kHinge;
      j.left_frame_guid = frame_at(x + half);
      j.right_frame_guid = frame_at(x - half);
      next.loose_joints.push_back(j);
      selected = {SelectionKind::kLooseJoint, 0,
                  static_cast<int>(next.loose_joints.size()) - 1};
      break;
    }
  }
  Commit(std::move(next), selected);
}

void Design::DetachLock() {
  if (selection_.kind != SelectionKind::kLock) {
    throw DesignError("select a lock first");
  }
  Scenario next = scenario_;
  Robot& robot = next.robots.at(selection_.robot);
  if (selection_.index < 0 ||
      selection_.index >= static_cast<int>(robot.locks.size())) {
    throw DesignError("there is no lock " + std::to_string(selection_.index));
  }
  if (IsChainLock(robot, robot.locks[selection_.index])) {
    throw DesignError(
        "this lock holds the chain together (it joins two parts next to "
        "each other): remove or move a part instead, or set a breaking "
        "force so it breaks during the run");
  }
  robot.locks.erase(robot.locks.begin() + selection_.index);
  Commit(std::move(next), {SelectionKind::kRobot, selection_.robot, 0});
}

std::vector<LockEnd> Design::LockEnds(int robot) const {
  if (robot < 0 || robot >= static_cast<int>(scenario_.robots.size())) {
    return {};
  }
  return EndsOf(scenario_.robots[robot]);
}

std::vector<LockEnd> Design::AttachableTo(int robot,
                                          const std::string& from) const {
  std::vector<LockEnd> out;
  if (robot < 0 || robot >= static_cast<int>(scenario_.robots.size())) {
    return out;
  }
  const Robot& r = scenario_.robots[robot];
  for (const LockEnd& end : EndsOf(r)) {
    if (end.guid != from && !Joined(r, from, end.guid)) out.push_back(end);
  }
  return out;
}

void Design::AttachLock(int robot, const std::string& a, const std::string& b) {
  if (robot < 0 || robot >= static_cast<int>(scenario_.robots.size())) {
    throw DesignError("there is no robot " + std::to_string(robot));
  }
  Scenario next = scenario_;
  Robot& r = next.robots[robot];
  std::string a_name, b_name;
  for (const LockEnd& end : EndsOf(r)) {
    if (end.guid == a) a_name = end.name;
    if (end.guid == b) b_name = end.name;
  }
  if (a_name.empty() || b_name.empty()) {
    throw DesignError("a lock joins two frames or sensor modules of " +
                      RobotName(next, robot));
  }
  if (a == b) throw DesignError("a lock joins two different parts");
  if (Joined(r, a, b)) {
    throw DesignError(a_name + " and " + b_name + " are joined already");
  }
  std::set<std::string> used = AllGuids(next);
  Joint lock;
  lock.guid = FreshGuid(used, RobotName(next, robot) + "/loop");
  lock.type = JointType::kLock;
  lock.left_frame_guid = a;
  lock.right_frame_guid = b;
  r.locks.push_back(lock);
  const Selection selected{SelectionKind::kLock, robot,
                           static_cast<int>(r.locks.size()) - 1};
  Commit(std::move(next), selected);
}

std::vector<LockEnd> Design::LooseEnds() const {
  std::vector<LockEnd> ends;
  for (const Frame& f : scenario_.loose_frames) {
    ends.push_back({f.guid, "loose frame " + f.guid});
  }
  for (const SensorModule& sm : scenario_.loose_sensor_modules) {
    ends.push_back({sm.guid, "loose sensor module " + sm.guid});
  }
  return ends;
}

std::vector<LockEnd> Design::LooseJoinableTo(const std::string& from) const {
  std::vector<LockEnd> out;
  for (const LockEnd& end : LooseEnds()) {
    if (end.guid != from && !JoinedLoose(scenario_, from, end.guid)) {
      out.push_back(end);
    }
  }
  return out;
}

void Design::JoinLoose(const std::string& a, const std::string& b,
                       JointType type) {
  std::string a_name, b_name;
  for (const LockEnd& end : LooseEnds()) {
    if (end.guid == a) a_name = end.name;
    if (end.guid == b) b_name = end.name;
  }
  if (a_name.empty() || b_name.empty()) {
    throw DesignError(
        "a loose joint joins two loose frames or loose sensor modules");
  }
  if (a == b) throw DesignError("a loose joint joins two different parts");
  if (JoinedLoose(scenario_, a, b)) {
    throw DesignError(a_name + " and " + b_name + " are joined already");
  }
  Scenario next = scenario_;
  Joint joint;
  joint.guid = FreshGuid(AllGuids(next), "loose/j");
  joint.type = type;
  joint.left_frame_guid = a;
  joint.right_frame_guid = b;
  next.loose_joints.push_back(joint);
  Commit(std::move(next), {SelectionKind::kLooseJoint, 0,
                           static_cast<int>(scenario_.loose_joints.size())});
}

void Design::MoveSelected(int steps) {
  if (!IsChainPart(selection_)) {
    throw DesignError("select a module or sensor module to move");
  }
  const Robot& robot = scenario_.robots.at(selection_.robot);
  const int at = SlotOf(ChainOrder(robot), selection_);
  const int to = at + steps;
  if (at < 0 || to < 0 || to >= static_cast<int>(ChainOrder(robot).size())) {
    throw DesignError("it is already at the end of the chain");
  }
  MovePart(selection_.robot, at, to);
}

void Design::MovePart(int robot, int from, int to) {
  if (robot < 0 || robot >= static_cast<int>(scenario_.robots.size())) {
    throw DesignError("there is no robot " + std::to_string(robot));
  }
  Scenario next = scenario_;
  const Robot& old = next.robots[robot];
  std::vector<ChainSlot> slots = ChainOrder(old);
  const int n = static_cast<int>(slots.size());
  if (from < 0 || from >= n || to < 0 || to >= n) {
    throw DesignError("the chain has no place " +
                      std::to_string(from < 0 || from >= n ? from : to));
  }
  if (from == to) return;
  const ChainSlot moved = slots[from];
  slots.erase(slots.begin() + from);
  slots.insert(slots.begin() + to, moved);
  try {
    next.robots[robot] =
        RelayoutFacing(old, slots, OptionsOf(old), scenario_.base_dir);
  } catch (const std::invalid_argument& e) {
    throw DesignError("cannot move it: " + std::string(e.what()));
  }
  Commit(std::move(next), SelectionAt(slots, robot, to));
}

void Design::MoveOnGround(const Selection& what, const GroundMove& move) {
  if (move.empty()) return;
  Scenario next = scenario_;
  switch (what.kind) {
    case SelectionKind::kRobot:
    case SelectionKind::kModule:
    case SelectionKind::kSensorModule:
      if (what.robot < 0 || what.robot >= static_cast<int>(next.robots.size()))
        throw DesignError("there is no robot " + std::to_string(what.robot));
      MoveRobot(&next.robots[what.robot], move);
      break;
    case SelectionKind::kSceneObject:
      if (what.index < 0 ||
          what.index >= static_cast<int>(next.scene_objects.size()))
        throw DesignError("there is no object " + std::to_string(what.index));
      MoveObject(&next.scene_objects[what.index], move);
      break;
    case SelectionKind::kLooseFrame:
    case SelectionKind::kLooseSensorModule:
    case SelectionKind::kLooseJoint: {
      const std::vector<Selection> group = LooseGroup(next, what);
      if (group.empty()) throw DesignError("there is no such loose part");
      MoveLooseGroup(&next, group, move);
      break;
    }
    default:
      throw DesignError(
          "only robots, objects and loose parts move on the "
          "ground");
  }
  Commit(std::move(next), selection_);
}

SensorModule& Design::SelectedSensorModule(Scenario* next) const {
  if (selection_.kind == SelectionKind::kLooseSensorModule) {
    return next->loose_sensor_modules.at(selection_.index);
  }
  if (selection_.kind != SelectionKind::kSensorModule) {
    throw DesignError("select a sensor module first");
  }
  return next->robots.at(selection_.robot).sensor_modules.at(selection_.index);
}

void Design::SetSensorKind(const SensorKind& kind, bool on) {
  Scenario next = scenario_;
  SensorModule& sm = SelectedSensorModule(&next);
  if (kind.set == nullptr || on == (kind.count(sm) > 0)) return;
  if (kind.mount == SensorMount::kPlate &&
      selection_.kind == SelectionKind::kLooseSensorModule) {
    throw DesignError(std::string("a ") + kind.label +
                      " is what a robot's chain rests on: a loose sensor "
                      "module has no chain, so it takes none");
  }
  if (kind.mount != SensorMount::kPlate) {
    kind.set(sm, on);
    Commit(std::move(next), selection_);
    return;
  }
  // A plate changes how the chain rests: laid out again, plates and their
  // locks named as MakeChain names them, the chain on its plates or on the
  // ground.
  Robot& robot = next.robots[selection_.robot];
  ChainOptions options = OptionsOf(robot);  // the origin under the old lift
  kind.set(sm, on);
  options.force_sensors = false;
  for (const SensorModule& s : robot.sensor_modules) {
    for (const SensorKind& k : SensorKinds()) {
      if (k.mount == SensorMount::kPlate && k.count(s) > 0) {
        options.force_sensors = true;
      }
    }
  }
  try {
    robot =
        RelayoutFacing(robot, ChainOrder(robot), options, scenario_.base_dir);
  } catch (const std::invalid_argument& e) {
    throw DesignError(e.what());
  }
  Commit(std::move(next), selection_);
}

void Design::SetForcePlate(bool on) {
  SetSensorKind(*FindSensorKind("force"), on);
}

void Design::AddDistanceSensor(int face) {
  Scenario next = scenario_;
  AddRay(&SelectedSensorModule(&next), face);
  RefuseUselessRay(scenario_, next);
  Commit(std::move(next), selection_);
}

std::vector<int> Design::OpenRayFaces() const {
  std::vector<int> faces;
  if (selection_.kind != SelectionKind::kSensorModule &&
      selection_.kind != SelectionKind::kLooseSensorModule) {
    return faces;
  }
  for (int face = 0; face < 6; ++face) {
    Scenario next = scenario_;
    try {
      AddRay(&SelectedSensorModule(&next), face);
      ValidateScenario(next);
      RefuseUselessRay(scenario_, next);
      faces.push_back(face);
    } catch (const std::exception&) {
      // taken, full, or looking into the robot
    }
  }
  return faces;
}

void Design::AddRay(SensorModule* sm, int face) {
  if (face < 0 || face > 5) {
    throw DesignError("face " + std::to_string(face) + ": expected 0..5 (" +
                      std::string(kSensorFaceList) + ")");
  }
  if (sm->distance_sensors.size() >= 6) {
    throw DesignError("a sensor module carries at most six distance sensors");
  }
  for (const DistanceSensor& d : sm->distance_sensors) {
    if (d.sensor_position == face) {
      throw DesignError("face " + std::to_string(face) +
                        " already has a distance sensor");
    }
  }
  auto used = [&](const std::string& guid) {
    for (const DistanceSensor& d : sm->distance_sensors) {
      if (d.guid == guid) return true;
    }
    return false;
  };
  int k = 0;
  while (used(sm->guid + "/d" + std::to_string(k))) ++k;
  DistanceSensor ray;
  ray.guid = sm->guid + "/d" + std::to_string(k);
  ray.sensor_position = face;
  ray.ray_direction = SensorFaceNormal(face);
  sm->distance_sensors.push_back(ray);
  sm->distance_sensor_locks.push_back(
      MakeLock(ray.guid + "_lock", sm->guid, ray.guid));
  PlaceMounted(sm);
}

void Design::RemoveDistanceSensor(int k) {
  Scenario next = scenario_;
  SensorModule& sm = SelectedSensorModule(&next);
  if (k < 0 || k >= static_cast<int>(sm.distance_sensors.size())) {
    throw DesignError("no distance sensor " + std::to_string(k));
  }
  const std::string guid = sm.distance_sensors[k].guid;
  sm.distance_sensors.erase(sm.distance_sensors.begin() + k);
  auto& locks = sm.distance_sensor_locks;
  const auto lock =
      std::find_if(locks.begin(), locks.end(), [&](const Joint& j) {
        return !guid.empty() && j.right_frame_guid == guid;
      });
  if (lock != locks.end()) {
    locks.erase(lock);
  } else if (k < static_cast<int>(locks.size())) {
    locks.erase(locks.begin() + k);
  }
  PlaceMounted(&sm);
  Commit(std::move(next), selection_);
}

std::vector<Camera>& Design::SelectedCameras(Scenario* next,
                                             std::string* owner_guid) const {
  if (selection_.kind == SelectionKind::kSceneObject) {
    SceneObject& o = next->scene_objects.at(selection_.index);
    *owner_guid = o.guid;
    return o.cameras;
  }
  if (selection_.kind != SelectionKind::kSensorModule &&
      selection_.kind != SelectionKind::kLooseSensorModule) {
    throw DesignError("select a sensor module or a scene object first");
  }
  SensorModule& sm = SelectedSensorModule(next);
  *owner_guid = sm.guid;
  return sm.cameras;
}

void Design::AddCamera(int face) {
  Scenario next = scenario_;
  std::string guid;
  MountCamera(&SelectedCameras(&next, &guid), guid, face);
  RefuseUselessRay(scenario_, next);
  Commit(std::move(next), selection_);
}

std::vector<int> Design::OpenCameraFaces() const {
  std::vector<int> faces;
  if (selection_.kind != SelectionKind::kSensorModule &&
      selection_.kind != SelectionKind::kLooseSensorModule &&
      selection_.kind != SelectionKind::kSceneObject) {
    return faces;
  }
  for (int face = 0; face < 6; ++face) {
    Scenario next = scenario_;
    try {
      std::string guid;
      MountCamera(&SelectedCameras(&next, &guid), guid, face);
      ValidateScenario(next);
      RefuseUselessRay(scenario_, next);
      faces.push_back(face);
    } catch (const std::exception&) {
      // taken, full, or looking into the robot
    }
  }
  return faces;
}

void Design::MountCamera(std::vector<Camera>* cameras,
                         const std::string& owner_guid, int face) {
  if (face < 0 || face > 5) {
    throw DesignError("face " + std::to_string(face) + ": expected 0..5 (" +
                      std::string(kSensorFaceList) + ")");
  }
  if (cameras->size() >= 6) {
    throw DesignError("a part carries at most six cameras");
  }
  for (const Camera& c : *cameras) {
    if (c.sensor_position == face) {
      throw DesignError("face " + std::to_string(face) + " (" +
                        kSensorFaceNames[face] + ") already has a camera");
    }
  }
  auto used = [&](const std::string& guid) {
    for (const Camera& c : *cameras) {
      if (c.guid == guid) return true;
    }
    return false;
  };
  int k = 0;
  while (used(owner_guid + "/c" + std::to_string(k))) ++k;
  Camera camera;
  camera.guid = owner_guid + "/c" + std::to_string(k);
  camera.sensor_position = face;
  cameras->push_back(camera);
}

void Design::RemoveCamera(int k) {
  Scenario next = scenario_;
  std::string guid;
  std::vector<Camera>& cameras = SelectedCameras(&next, &guid);
  if (k < 0 || k >= static_cast<int>(cameras.size())) {
    throw DesignError("no camera " + std::to_string(k));
  }
  cameras.erase(cameras.begin() + k);
  Commit(std::move(next), selection_);
}

namespace {

FieldRef FindField(Scenario& s, const FieldAddress& a) {
  for (const FieldGroup& g : InspectorFields(s, a.part)) {
    if (g.sub != a.sub) continue;
    for (const FieldRef& f : g.fields) {
      if (a.field == f.info().xml) return f;
    }
  }
  throw DesignError("no field '" + a.field + "' in " + ToString(a.part.kind) +
                    (a.sub.empty() ? "" : "/" + a.sub));
}

}  // namespace

std::string Design::FieldText(const FieldAddress& address) const {
  Scenario copy = scenario_;
  return FindField(copy, address).GetText();
}

void Design::SetField(const FieldAddress& address, const std::string& text) {
  Scenario next = scenario_;
  const FieldRef field = FindField(next, address);
  if (field.GetText() == text) return;
  try {
    field.SetText(text);
  } catch (const FieldError& e) {
    throw DesignError(e.what());
  }
  // A part that grows or shrinks keeps the chain together: the parts
  // behind it slide to stay attached.
  const bool length =
      (address.field == "scale" && address.sub.rfind("frames[", 0) == 0) ||
      (address.field == "size" && address.sub.empty());
  if (length && IsChainPart(address.part)) {
    Restack(&next.robots.at(address.part.robot), scenario_.base_dir);
  }
  // A plate or ray moved to another face sits on that face; a ray that
  // looked straight out of its old face looks out of the new one.
  // A face out of range is left to the validator's message.
  if (address.part.kind == SelectionKind::kSensorModule &&
      !address.sub.empty()) {
    try {
      SensorModule& sm = next.robots.at(address.part.robot)
                             .sensor_modules.at(address.part.index);
      const std::string prefix = "distance_sensors[";
      if (address.field == "sensorPosition" &&
          address.sub.rfind(prefix, 0) == 0) {
        const int k = std::stoi(address.sub.substr(prefix.size()));
        const DistanceSensor& before = scenario_.robots[address.part.robot]
                                           .sensor_modules[address.part.index]
                                           .distance_sensors.at(k);
        DistanceSensor& d = sm.distance_sensors.at(k);
        if (before.ray_direction.isApprox(
                SensorFaceNormal(before.sensor_position))) {
          d.ray_direction = SensorFaceNormal(d.sensor_position);
        }
      }
      PlaceMounted(&sm);
    } catch (const std::out_of_range&) {
    }
  }
  // Euler angles place nothing; keep the quaternion that does in step.
  if (address.field == "rotation" &&
      address.part.kind == SelectionKind::kSceneObject) {
    SceneObject& o = next.scene_objects[address.part.index];
    const Eigen::Vector3d r = o.rotation * M_PI / 180;
    o.quat_rotation = Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
                      Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX());
  }
  // A loose hinge made a Lock keeps no servo: a lock never turns, and the
  // validator refuses a servo on one.
  if (address.part.kind == SelectionKind::kLooseJoint &&
      address.field == "type" && address.part.index >= 0 &&
      address.part.index < static_cast<int>(next.loose_joints.size())) {
    Joint& j = next.loose_joints[address.part.index];
    if (j.type == JointType::kLock) j.servo = false;
  }
  RefuseUselessRay(scenario_, next);
  Commit(std::move(next), selection_);
}

void Design::SetTerrain(const std::string& image, double height,
                        double meters_per_pixel) {
  Scenario next = scenario_;
  next.scene.height_image = image;
  next.scene.height = height;
  next.scene.meters_per_pixel = meters_per_pixel;
  Commit(std::move(next), {SelectionKind::kScene, 0, 0});
}

void Design::SetModuleMesh(const std::string& mesh, bool every_of_kind) {
  if (selection_.kind != SelectionKind::kModule) {
    throw DesignError("select a module first");
  }
  Scenario next = scenario_;
  Robot& robot = next.robots.at(selection_.robot);
  const Module& chosen = robot.modules.at(selection_.index);
  // Named relative to the design's folder when inside it, so the design
  // and its meshes move together.
  std::string shape = mesh;
  if (!scenario_.base_dir.empty()) {
    const std::filesystem::path rel =
        std::filesystem::path(mesh).lexically_normal().lexically_relative(
            scenario_.base_dir);
    if (!rel.empty() && rel.native().rfind("..", 0) != 0) shape = rel.string();
  }
  const Axis axis = chosen.axis;
  const int index = selection_.index;
  for (int i = 0; i < static_cast<int>(robot.modules.size()); ++i) {
    Module& m = robot.modules[i];
    if (every_of_kind ? m.axis != axis : i != index) continue;
    for (Frame& f : m.frames) {
      // A box's scale is its size; a mesh's multiplies the file's units.
      if (!f.is_mesh()) f.scale = Eigen::Vector3d::Ones();
      f.shape = shape;
    }
  }
  // The mesh is measured now: an unreadable one is refused here.
  try {
    for (Frame& f : robot.modules.at(index).frames) {
      FrameBounds(f, next.base_dir);
    }
  } catch (const std::exception& e) {
    throw DesignError(e.what());
  }
  Restack(&robot, next.base_dir);
  Commit(std::move(next), selection_);
}

void Design::ScaleMesh(const std::string& shape, double factor) {
  Scenario next = scenario_;
  bool found = false;
  for (Robot& robot : next.robots) {
    bool changed = false;
    for (Module& m : robot.modules) {
      for (Frame& f : m.frames) {
        if (f.shape != shape) continue;
        f.scale *= factor;
        changed = true;
      }
    }
    if (changed) Restack(&robot, next.base_dir);
    found = found || changed;
  }
  if (!found) throw DesignError("no frame has that mesh");
  Commit(std::move(next), selection_);
}

std::vector<Design::OversizedMesh> Design::OversizedMeshes() const {
  std::vector<OversizedMesh> out;
  // Each file read once (a chain often repeats one mesh): its size at
  // scale 1, NaN when it cannot be read.
  std::map<std::string, Eigen::Vector3d> unscaled;
  for (const Robot& robot : scenario_.robots) {
    for (const Module& m : robot.modules) {
      for (const Frame& f : m.frames) {
        if (!f.is_mesh()) continue;
        auto known = unscaled.find(f.shape);
        if (known == unscaled.end()) {
          Frame one = f;
          one.scale = Eigen::Vector3d::Ones();
          Eigen::Vector3d size = Eigen::Vector3d::Constant(
              std::numeric_limits<double>::quiet_NaN());
          try {
            size = FrameBounds(one, scenario_.base_dir).sizes();
          } catch (const std::exception&) {
            // Left to the validator, which says why it cannot be read.
          }
          known = unscaled.emplace(f.shape, size).first;
        }
        if (!known->second.allFinite()) continue;
        const double longest =
            known->second.cwiseProduct(f.scale.cwiseAbs()).maxCoeff();
        if (longest <= kMeshLooksLikeMillimetres) continue;
        auto same = std::find_if(out.begin(), out.end(), [&](const auto& o) {
          return o.shape == f.shape;
        });
        if (same == out.end()) {
          out.push_back({f.shape, longest});
        } else {
          same->longest = std::max(same->longest, longest);
        }
      }
    }
  }
  return out;
}

void Design::ApplyTemplate(const TemplateOptions& options) {
  Scenario next = MakeTemplateScenario(options);
  next.base_dir = scenario_.base_dir;
  Commit(std::move(next), {SelectionKind::kModule, 0, 0});
}

void Design::Clear() {
  Scenario next = EmptyScenario();
  next.base_dir = scenario_.base_dir;
  Commit(std::move(next), {});
}

void Design::Undo() {
  if (undo_.empty()) return;
  redo_.push_back({std::move(scenario_), selection_});
  scenario_ = std::move(undo_.back().scenario);
  selection_ = undo_.back().selection;
  undo_.pop_back();
  Changed();
}

void Design::Redo() {
  if (redo_.empty()) return;
  undo_.push_back({std::move(scenario_), selection_});
  scenario_ = std::move(redo_.back().scenario);
  selection_ = redo_.back().selection;
  redo_.pop_back();
  Changed();
}

void Design::SetRunSettings(const RunSettings& run) {
  if (scenario_.run && *scenario_.run == run) return;
  Scenario probe;  // the rules of <run> alone: no meshes to load
  probe.run = run;
  try {
    ValidateScenario(probe);
  } catch (const ScenarioError& e) {
    throw DesignError("run settings: " + e.path() + ": " + e.message());
  }
  scenario_.run = run;
  dirty_ = WriteScenarioString(scenario_) != saved_text_;
}

void Design::SetOptimizationSettings(
    const std::optional<OptimizationSettings>& setup) {
  if (scenario_.optimization == setup) return;
  Scenario probe;  // the rules of <optimization> alone
  probe.optimization = setup;
  try {
    ValidateScenario(probe);
  } catch (const ScenarioError& e) {
    throw DesignError("optimisation setup: " + e.path() + ": " + e.message());
  }
  scenario_.optimization = setup;
  dirty_ = WriteScenarioString(scenario_) != saved_text_;
}

void Design::Save(bool embed_assets) {
  if (path_.empty()) throw std::runtime_error("no file name: use Save As");
  if (embed_assets) {
    Scenario copy = scenario_;
    if (copy.base_dir.empty()) {
      copy.base_dir = std::filesystem::path(path_).parent_path().string();
    }
    EmbedAssetFiles(copy);
    WriteScenarioFile(copy, path_);
  } else {
    WriteScenarioFile(scenario_, path_);
  }
  saved_text_ = WriteScenarioString(scenario_);
  dirty_ = false;
}

void Design::SaveAs(const std::string& path, bool embed_assets) {
  const std::string previous = path_;
  path_ = path;
  try {
    Save(embed_assets);
  } catch (...) {
    path_ = previous;
    throw;
  }
}

}  // namespace mrsim::studio

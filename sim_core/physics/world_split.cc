#include "sim_core/physics/world_split.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>

#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/physics/physics_state_fields.h"

namespace mrsim {
namespace {

// Robots whose boxes come within this distance share a world. Contacts
// need touching parts (the geoms' margin is added on top), so any value
// >= 0 keeps the physics of one world; a few centimetres spare merging
// back and forth between two parts that brush past each other.
constexpr double kMergeGap = 0.02;
constexpr char kSplitMagic[8] = {'M', 'R', 'S', 'I', 'M', 'S', 'W', '1'};

template <typename T>
void Put(std::vector<unsigned char>& out, const T* values, size_t n) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(values);
  out.insert(out.end(), bytes, bytes + n * sizeof(T));
}

// Axis-aligned box around a robot's geoms in the current state.
struct Box {
  int world = -1;
  double lo[3] = {1e300, 1e300, 1e300};
  double hi[3] = {-1e300, -1e300, -1e300};
  bool Overlaps(const Box& o) const {
    for (int i = 0; i < 3; ++i) {
      if (lo[i] > o.hi[i] || o.lo[i] > hi[i]) return false;
    }
    return true;
  }
};

Box GeomBox(const mjModel* m, const mjData* d, const std::vector<int>& geoms) {
  Box box;
  for (int g : geoms) {
    double half[3];
    const mjtNum* x = d->geom_xmat + 9 * g;
    if (m->geom_type[g] == mjGEOM_BOX) {
      const mjtNum* s = m->geom_size + 3 * g;
      for (int i = 0; i < 3; ++i) {
        half[i] = std::abs(x[3 * i]) * s[0] + std::abs(x[3 * i + 1]) * s[1] +
                  std::abs(x[3 * i + 2]) * s[2];
      }
    } else {
      half[0] = half[1] = half[2] = m->geom_rbound[g];
    }
    const double pad = m->geom_margin[g] + kMergeGap / 2;
    for (int i = 0; i < 3; ++i) {
      box.lo[i] = std::min(box.lo[i], d->geom_xpos[3 * g + i] - half[i] - pad);
      box.hi[i] = std::max(box.hi[i], d->geom_xpos[3 * g + i] + half[i] + pad);
    }
  }
  return box;
}

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

WorldSplit::WorldSplit(const Scenario& scenario)
    : scenario_(scenario), nrobots_(static_cast<int>(scenario.robots.size())) {
  for (int r = 0; r < nrobots_; ++r) entities_.push_back(r);
  for (size_t i = 0; i < scenario.scene_objects.size(); ++i) {
    if (!scenario.scene_objects[i].is_static) {
      entities_.push_back(nrobots_ + static_cast<int>(i));
    }
  }
}
WorldSplit::~WorldSplit() = default;

std::unique_ptr<WorldSplit> WorldSplit::Make(const Scenario& scenario) {
  const int n = static_cast<int>(scenario.robots.size());
  // One robot (the common case) runs as one world with its objects, bit
  // for bit as it always did: splitting off a ball saves next to nothing.
  if (n < 2 || !scenario.loose_frames.empty() ||
      !scenario.loose_joints.empty() ||
      !scenario.loose_sensor_modules.empty()) {
    return nullptr;
  }
  std::set<std::string> names;
  for (int r = 0; r < n; ++r) {
    if (!names.insert(RobotName(scenario, r)).second) return nullptr;
  }
  std::unique_ptr<WorldSplit> split(new WorldSplit(scenario));
  if (split->entities_.size() < 2) return nullptr;
  std::vector<std::vector<int>> groups;
  for (int e : split->entities_) groups.push_back({e});
  split->BuildWorlds(groups);
  bool merged = false;
  while (split->MergeTouching()) merged = true;
  if (split->worlds_.size() < 2) return nullptr;
  split->initial_groups_ = split->Groups();
  // Fresh builds of the merged groups, exactly as Reset makes them.
  if (merged) split->BuildWorlds(split->initial_groups_);
  return split;
}

WorldSplit::World WorldSplit::MakeWorld(
    const std::vector<int>& entities) const {
  Scenario part = scenario_;
  part.robots.clear();
  World w;
  w.entities = entities;
  // Dynamic scene objects of other worlds are left out; static ones are
  // in every world.
  std::vector<bool> skip(scenario_.scene_objects.size(), false);
  for (size_t i = 0; i < skip.size(); ++i) {
    skip[i] = !scenario_.scene_objects[i].is_static;
  }
  for (int e : entities) {
    if (e < nrobots_) {
      part.robots.push_back(scenario_.robots[e]);
      part.robots.back().name = RobotName(scenario_, e);
      w.robots.push_back(e);
    } else {
      skip[e - nrobots_] = false;
    }
  }
  w.physics.reset(new Physics(part, w.robots, skip));
  const mjModel* m = w.physics->model();
  for (int e : entities) {
    // A robot's bodies are "<robot>/...", an object's "scene/obj<i>".
    const std::string prefix = e < nrobots_
                                   ? RobotName(scenario_, e) + "/"
                                   : mjcf_names::SceneObject(e - nrobots_);
    const bool exact = e >= nrobots_;
    std::vector<int> geoms;
    for (int i = 0; i < m->ngeom; ++i) {
      const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[i]);
      if (body &&
          (exact ? prefix == body
                 : std::strncmp(body, prefix.c_str(), prefix.size()) == 0)) {
        geoms.push_back(i);
      }
    }
    w.geoms.push_back(std::move(geoms));
  }
  return w;
}

void WorldSplit::IndexRobots() {
  world_of_robot_.assign(nrobots_, -1);
  local_of_robot_.assign(nrobots_, -1);
  for (size_t w = 0; w < worlds_.size(); ++w) {
    for (size_t k = 0; k < worlds_[w].robots.size(); ++k) {
      world_of_robot_[worlds_[w].robots[k]] = static_cast<int>(w);
      local_of_robot_[worlds_[w].robots[k]] = static_cast<int>(k);
    }
  }
}

void WorldSplit::Install(World* world, bool with_gap) {
  const Physics* self = world->physics.get();
  world->physics->SetOtherWorldsRay(
      [this, self](const double* point, const double* xmat, double range) {
        return RayOthers(self, point, xmat, range);
      });
  if (with_gap && gap_set_) world->physics->SetRealityGap(gap_);
}

void WorldSplit::BuildWorlds(const std::vector<std::vector<int>>& groups) {
  std::vector<World> fresh;
  for (const std::vector<int>& g : groups) {
    fresh.push_back(MakeWorld(g));
    Install(&fresh.back());
  }
  worlds_ = std::move(fresh);
  IndexRobots();
  view_stale_ = true;
}

std::vector<std::vector<int>> WorldSplit::Groups() const {
  std::vector<std::vector<int>> groups;
  for (const World& w : worlds_) groups.push_back(w.entities);
  return groups;
}

std::vector<std::vector<int>> WorldSplit::Touching() const {
  std::vector<Box> boxes;
  for (size_t w = 0; w < worlds_.size(); ++w) {
    const mjModel* m = worlds_[w].physics->model();
    const mjData* d = worlds_[w].physics->data();
    for (const std::vector<int>& geoms : worlds_[w].geoms) {
      if (geoms.empty()) continue;
      boxes.push_back(GeomBox(m, d, geoms));
      boxes.back().world = static_cast<int>(w);
    }
  }
  std::vector<int> parent(worlds_.size());
  std::iota(parent.begin(), parent.end(), 0);
  bool any = false;
  for (size_t i = 0; i < boxes.size(); ++i) {
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      if (boxes[i].world == boxes[j].world || !boxes[i].Overlaps(boxes[j])) {
        continue;
      }
      const int a = Find(parent, boxes[i].world);
      const int b = Find(parent, boxes[j].world);
      if (a != b) {
        parent[std::max(a, b)] = std::min(a, b);
        any = true;
      }
    }
  }
  std::vector<std::vector<int>> groups;
  if (!any) return groups;
  std::vector<std::vector<int>> members(worlds_.size());
  for (size_t w = 0; w < worlds_.size(); ++w) {
    members[Find(parent, static_cast<int>(w))].push_back(static_cast<int>(w));
  }
  for (auto& m : members) {
    if (m.size() > 1) groups.push_back(std::move(m));
  }
  return groups;
}

bool WorldSplit::MergeTouching() {
  const std::vector<std::vector<int>> touching = Touching();
  if (touching.empty()) return false;
  std::vector<bool> gone(worlds_.size(), false);
  std::vector<World> next;
  for (const std::vector<int>& group : touching) {
    std::vector<int> entities;
    std::vector<const Physics*> parts;
    for (int w : group) {
      entities.insert(entities.end(), worlds_[w].entities.begin(),
                      worlds_[w].entities.end());
      parts.push_back(worlds_[w].physics.get());
      gone[w] = true;
    }
    std::sort(entities.begin(), entities.end());
    World merged = MakeWorld(entities);
    Install(&merged);
    merged.physics->AbsorbState(parts);
    next.push_back(std::move(merged));
  }
  for (size_t w = 0; w < worlds_.size(); ++w) {
    if (!gone[w]) next.push_back(std::move(worlds_[w]));
  }
  // Worlds in the order of their first entity, whatever merged when.
  std::sort(next.begin(), next.end(), [](const World& a, const World& b) {
    return a.entities.front() < b.entities.front();
  });
  worlds_ = std::move(next);
  IndexRobots();
  view_stale_ = true;
  return true;
}

void WorldSplit::Step() {
  // Every world takes its step even when one fails, so all keep one time;
  // the first failure is reported after.
  std::exception_ptr failure;
  for (World& w : worlds_) {
    try {
      w.physics->Step();
    } catch (const PhysicsError&) {
      if (!failure) failure = std::current_exception();
    }
  }
  view_stale_ = true;
  if (failure) std::rethrow_exception(failure);
  MergeTouching();
}

void WorldSplit::Reset() {
  if (Groups() == initial_groups_) {
    for (World& w : worlds_) w.physics->Reset();
  } else {
    BuildWorlds(initial_groups_);
  }
  view_stale_ = true;
}

void WorldSplit::SetRealityGap(const RealityGap& gap) {
  for (World& w : worlds_) w.physics->SetRealityGap(gap);
  gap_ = gap;
  gap_set_ = true;
}

double WorldSplit::time() const { return worlds_.front().physics->time(); }

Physics& WorldSplit::world_of(int robot, int* local) {
  *local = local_of_robot_.at(robot);
  return *worlds_[world_of_robot_.at(robot)].physics;
}

const Physics& WorldSplit::world_of(int robot, int* local) const {
  *local = local_of_robot_.at(robot);
  return *worlds_[world_of_robot_.at(robot)].physics;
}

double WorldSplit::RayOthers(const Physics* self, const double* point,
                             const double* xmat, double range) const {
  const mjtNum dir[3] = {xmat[0], xmat[3], xmat[6]};
  double best = range;
  for (const World& w : worlds_) {
    if (w.physics.get() == self) continue;
    int geom = -1;
    // Every world holds the ground and the static objects, so those are
    // seen in the ray's own world already; here the other robots.
    const mjtNum dist = mj_ray(w.physics->model(), w.physics->data(), point,
                               dir, nullptr, 1, -1, &geom);
    if (dist >= 0 && geom >= 0) best = std::min(best, dist);
  }
  return best;
}

void WorldSplit::MapView(const mjModel* v, World* world) const {
  const mjModel* m = world->physics->model();
  auto id = [v](mjtObj type, const char* name) {
    const int i = name ? mj_name2id(v, type, name) : -1;
    if (i < 0) {
      throw std::logic_error(fmt::format("the scene's model has no {} '{}'",
                                         mju_type2Str(type),
                                         name ? name : "(unnamed)"));
    }
    return i;
  };
  world->qpos.clear();
  world->dof.clear();
  world->ctrl.clear();
  world->body.clear();
  world->sensor.clear();
  for (int j = 0; j < m->njnt; ++j) {
    const int vj = id(mjOBJ_JOINT, mj_id2name(m, mjOBJ_JOINT, j));
    const int type = m->jnt_type[j];
    const int nq = type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
    const int nv = type == mjJNT_FREE ? 6 : type == mjJNT_BALL ? 3 : 1;
    world->qpos.push_back({m->jnt_qposadr[j], v->jnt_qposadr[vj], nq});
    world->dof.push_back({m->jnt_dofadr[j], v->jnt_dofadr[vj], nv});
  }
  for (int a = 0; a < m->nu; ++a) {
    world->ctrl.push_back(
        {a, id(mjOBJ_ACTUATOR, mj_id2name(m, mjOBJ_ACTUATOR, a)), 1});
  }
  for (int b = 1; b < m->nbody; ++b) {
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    if (name) world->body.push_back({6 * b, 6 * id(mjOBJ_BODY, name), 6});
  }
  for (int s = 0; s < m->nsensor; ++s) {
    const int vs = id(mjOBJ_SENSOR, mj_id2name(m, mjOBJ_SENSOR, s));
    world->sensor.push_back(
        {m->sensor_adr[s], v->sensor_adr[vs], m->sensor_dim[s]});
  }
  world->mapped = true;
}

const std::vector<WorldSplit::Run>& WorldSplit::World::of(StatePer per) const {
  switch (per) {
    case StatePer::kJointPosition:
      return qpos;
    case StatePer::kDof:
      return dof;
    case StatePer::kActuator:
      return ctrl;
    case StatePer::kBody:
      return body;
    case StatePer::kSensordata:
      return sensor;
    default:
      throw std::logic_error("a split scene's view has no such array");
  }
}

void WorldSplit::SyncView(const mjModel* v, mjData* vd) {
  if (!view_stale_) return;
  for (World& w : worlds_) {
    if (!w.mapped) MapView(v, &w);
    const mjData* d = w.physics->data();
    for (const PhysicsStateField& f : kPhysicsStateFields) {
      if (!(f.copies & kStateView)) continue;
      for (const Run& r : w.of(f.per)) {
        mju_copy(vd->*f.array + r[1], d->*f.array + r[0], r[2]);
      }
    }
  }
  vd->time = time();
  mj_kinematics(v, vd);
  mj_comPos(v, vd);
  mj_comVel(v, vd);
  mj_camlight(v, vd);
  view_stale_ = false;
}

void WorldSplit::PushView(const mjData* vd) {
  // A stale view was not shown since the worlds moved on: nothing in it is
  // newer than the worlds.
  if (view_stale_) return;
  for (World& w : worlds_) {
    mjData* d = w.physics->mutable_data();
    bool moved = false;
    for (const Run& r : w.qpos) {
      moved |= std::memcmp(d->qpos + r[0], vd->qpos + r[1],
                           r[2] * sizeof(mjtNum)) != 0;
    }
    for (const Run& r : w.dof) {
      moved |= std::memcmp(d->qvel + r[0], vd->qvel + r[1],
                           r[2] * sizeof(mjtNum)) != 0;
      mju_copy(d->qfrc_applied + r[0], vd->qfrc_applied + r[1], r[2]);
    }
    for (const Run& r : w.body) {
      mju_copy(d->xfrc_applied + r[0], vd->xfrc_applied + r[1], r[2]);
    }
    if (moved) {
      for (const Run& r : w.qpos) {
        mju_copy(d->qpos + r[0], vd->qpos + r[1], r[2]);
      }
      for (const Run& r : w.dof) {
        mju_copy(d->qvel + r[0], vd->qvel + r[1], r[2]);
      }
      w.physics->AfterPoke();
    }
  }
}

bool WorldSplit::IsSplitState(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= sizeof(kSplitMagic) &&
         std::memcmp(bytes.data(), kSplitMagic, sizeof(kSplitMagic)) == 0;
}

std::vector<unsigned char> WorldSplit::SaveState() const {
  // One world holds the whole scene: its blob is that of the scene run as
  // one world (same model, same names).
  if (worlds_.size() == 1) return worlds_[0].physics->SaveState();
  std::vector<unsigned char> out;
  Put(out, kSplitMagic, sizeof(kSplitMagic));
  const int32_t nworlds = static_cast<int32_t>(worlds_.size());
  Put(out, &nworlds, 1);
  for (const World& w : worlds_) {
    const int32_t n = static_cast<int32_t>(w.entities.size());
    Put(out, &n, 1);
    std::vector<int32_t> ids(w.entities.begin(), w.entities.end());
    Put(out, ids.data(), ids.size());
    const std::vector<unsigned char> blob = w.physics->SaveState();
    const uint64_t size = blob.size();
    Put(out, &size, 1);
    Put(out, blob.data(), blob.size());
  }
  return out;
}

void WorldSplit::LoadState(const std::vector<unsigned char>& bytes) {
  const int nentities = static_cast<int>(entities_.size());
  std::vector<std::vector<int>> groups;
  std::vector<std::vector<unsigned char>> blobs;
  if (!IsSplitState(bytes)) {
    // A blob of the whole scene as one world (saved before worlds split,
    // or by a scene that merged into one).
    groups.push_back(entities_);
    blobs.push_back(bytes);
  } else {
    size_t at = sizeof(kSplitMagic);
    auto read = [&bytes, &at](void* dst, size_t n, const char* what) {
      if (bytes.size() - at < n) {
        throw std::invalid_argument(fmt::format(
            "physics state: the worlds section ends inside {} (byte {} of {})",
            what, at, bytes.size()));
      }
      std::memcpy(dst, bytes.data() + at, n);
      at += n;
    };
    int32_t nworlds = 0;
    read(&nworlds, sizeof nworlds, "the world count");
    if (nworlds < 1 || nworlds > nentities) {
      throw std::invalid_argument(fmt::format(
          "physics state: {} worlds saved; this scene has {} robots and "
          "dynamic scene objects",
          nworlds, nentities));
    }
    std::set<int> seen;
    for (int w = 0; w < nworlds; ++w) {
      int32_t n = 0;
      read(&n, sizeof n, "a world's part count");
      if (n < 1 || n > nentities) {
        throw std::invalid_argument(fmt::format(
            "physics state: world {} holds {} parts; this scene has {}", w, n,
            nentities));
      }
      std::vector<int32_t> ids(n);
      read(ids.data(), n * sizeof(int32_t), "a world's part list");
      for (int32_t i = 0; i < n; ++i) {
        if (!std::binary_search(entities_.begin(), entities_.end(), ids[i]) ||
            !seen.insert(ids[i]).second || (i > 0 && ids[i] <= ids[i - 1])) {
          throw std::invalid_argument(fmt::format(
              "physics state: world {} names part {} (expected robots 0..{} "
              "and dynamic scene objects {} + index, each once, ascending)",
              w, ids[i], nrobots_ - 1, nrobots_));
        }
      }
      uint64_t size = 0;
      read(&size, sizeof size, "a world's size");
      if (size > bytes.size() - at) {
        throw std::invalid_argument(
            fmt::format("physics state: world {} claims {} bytes, {} are left",
                        w, size, bytes.size() - at));
      }
      blobs.emplace_back(bytes.begin() + at, bytes.begin() + at + size);
      at += size;
      groups.emplace_back(ids.begin(), ids.end());
    }
    if (at != bytes.size() || static_cast<int>(seen.size()) != nentities) {
      throw std::invalid_argument(
          "physics state: the worlds section does not hold every robot and "
          "dynamic scene object, or has bytes after it");
    }
  }
  // Fresh worlds, loaded before they replace the running ones: a blob
  // that does not fit leaves the scene as it was.
  std::vector<World> fresh;
  for (size_t g = 0; g < groups.size(); ++g) {
    fresh.push_back(MakeWorld(groups[g]));
    if (gap_set_) fresh.back().physics->SetRealityGap(gap_);
    fresh.back().physics->LoadState(blobs[g]);
  }
  worlds_ = std::move(fresh);
  for (World& w : worlds_) Install(&w, false);
  IndexRobots();
  view_stale_ = true;
}

}  // namespace mrsim

// A scene of several robots run as separate MuJoCo worlds, one per group of
// robots that touch (or nearly do), so the cost per robot stays flat:
// MuJoCo 2.2 solves each world with dense matrices, and one world of 50
// robots costs far more than 50 worlds of one. Groups merge into one world
// as soon as their parts come close, before any contact between them could
// exist, so the physics is that of one world. Physics uses it internally;
// docs/physics.md ("Separate worlds") describes the rules.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/physics/reality_gap.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

enum class StatePer;  // sim_core/physics/physics_state_fields.h

class WorldSplit {
 public:
  // The worlds of `scenario`, or null when it runs as one world: fewer
  // than two robots, loose parts (they may reach
  // any robot), or everything close together from the start. A world
  // holds robots and dynamic scene objects ("entities": robot r is r,
  // scene object i is robots + i).
  static std::unique_ptr<WorldSplit> Make(const Scenario& scenario);
  ~WorldSplit();
  WorldSplit(const WorldSplit&) = delete;
  WorldSplit& operator=(const WorldSplit&) = delete;

  // Steps every world, then merges worlds whose robots came close.
  void Step();
  // Back to the initial worlds and state.
  void Reset();
  void SetRealityGap(const RealityGap& gap);
  double time() const;

  // The world holding robot `robot` (global index) and its index there.
  Physics& world_of(int robot, int* local);
  const Physics& world_of(int robot, int* local) const;
  int world_count() const { return static_cast<int>(worlds_.size()); }

  // The whole scene's state in the one-world model `m` (the view that
  // Physics::model()/data() show): positions, speeds, controls, forces,
  // sensors and the kinematics. Only when a world changed since the last
  // call, so poses written into the view (a preview) stay.
  void SyncView(const mjModel* m, mjData* d);
  // Writes what a caller poked into the view (applied forces, qpos, qvel)
  // back into the worlds.
  void PushView(const mjData* d);
  void MarkStale() { view_stale_ = true; }

  // A blob of the worlds' groups and each world's Physics::SaveState.
  // LoadState also takes a one-world blob of the whole scene (the scene
  // then runs as one world). Throws std::invalid_argument as
  // Physics::LoadState.
  std::vector<unsigned char> SaveState() const;
  void LoadState(const std::vector<unsigned char>& bytes);
  // True when `bytes` starts as a SaveState blob of a split scene.
  static bool IsSplitState(const std::vector<unsigned char>& bytes);

 private:
  // Source index, view index, count: one contiguous run to copy.
  using Run = std::array<int, 3>;
  struct World {
    std::unique_ptr<Physics> physics;
    std::vector<int> entities;            // ascending
    std::vector<int> robots;              // global indices, ascending
    std::vector<std::vector<int>> geoms;  // per entity: its geoms
    // Into the view; in mjtNum of their arrays.
    std::vector<Run> qpos, dof, ctrl, body, sensor;
    // The runs of an array of kPhysicsStateFields.
    const std::vector<Run>& of(StatePer per) const;
    bool mapped = false;
  };
  explicit WorldSplit(const Scenario& scenario);
  World MakeWorld(const std::vector<int>& entities) const;
  void IndexRobots();
  // Gives the world its view of the other worlds' rays and, with_gap,
  // the reality gap.
  void Install(World* world, bool with_gap = true);
  void BuildWorlds(const std::vector<std::vector<int>>& groups);
  // Groups of worlds whose robots' boxes overlap (union-find), as lists
  // of world indices; only groups of two or more.
  std::vector<std::vector<int>> Touching() const;
  // Merges touching worlds; false when none touch.
  bool MergeTouching();
  void MapView(const mjModel* m, World* world) const;
  std::vector<std::vector<int>> Groups() const;
  double RayOthers(const Physics* self, const double* point, const double* xmat,
                   double range) const;

  Scenario scenario_;
  int nrobots_ = 0;
  std::vector<int> entities_;  // every robot and dynamic scene object
  std::vector<World> worlds_;
  std::vector<int> world_of_robot_, local_of_robot_;
  std::vector<std::vector<int>> initial_groups_;
  RealityGap gap_;
  bool gap_set_ = false;
  bool view_stale_ = true;
};

}  // namespace mrsim

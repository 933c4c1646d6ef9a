// Turns a Scenario into MuJoCo MJCF text. The output is self-contained apart
// from mesh and height-field files, which it names by absolute path, so it
// opens in mujoco-simulate / mujoco-testxml. Names of bodies, joints,
// actuators, sites and sensors follow mjcf_names.h (docs/physics.md); part
// colours are part_look.h, face geometry face_geometry.h.
#pragma once

#include <Eigen/Core>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Servo model shared by the builder and the physics: a MuJoCo velocity
// actuator (force = Joint::velocity_gain * (ctrl - qvel), clamped to
// +-Joint::max_torque) on a hinge with the reflected rotor inertia of a
// geared servo (armature).
struct ServoModel {
  static constexpr double kArmature = 0.01;  // kg m^2
};

// Bodies nest at most this deep below a tree's root. Deeper chains are cut
// at a lock into sub-trees joined by a weld, so a chain of any length stays
// below XML parsers' nesting limits (tinyxml2: 100 elements).
constexpr int kMaxBodyDepth = 64;

// The MuJoCo geom group of contact-only boxes (MergeFlushFrames in the
// builder): one box for a rigid pair of flush module frames, which collides
// for both and weighs nothing. MuJoCo's viewers hide group 3 by default;
// code that walks geoms for looks or fluid drag skips it.
constexpr int kMjcfContactGroup = 3;

// Contact and constraint-row capacity of the model's mjData (MJCF <size>):
// what the model needs at rest; Physics grows them when a step needs more.
struct MjcfSizes {
  int nconmax = 0;
  int njmax = 0;
};
constexpr int kMjcfMinContacts = 200;
constexpr int kMjcfRowsPerContact = 4;  // pyramidal cone, condim 3
MjcfSizes MjcfSizesFor(int colliding_geoms, int welds, int hinges, int nv);
// The most constraint rows one mjData of a model with `nv` degrees of
// freedom can hold: MuJoCo 2.2 allocates 12 njmax^2 + 24 njmax nv bytes
// (the dense efc_AR, the Jacobian and their indices) in one buffer whose
// size is an int (under 2^31 bytes).
int MjcfMaxRows(int nv);

struct MjcfOptions {
  // false (export): the height field names a grey PNG by absolute path (the
  // scene's own PNG file, or the decoded image written to asset_dir, or to
  // the system temp directory when asset_dir is empty).
  // true (what Physics uses): the height field only declares nrow/ncol and
  // the caller fills mjModel::hfield_data with HeightFieldData().
  bool hfield_data_after_compile = false;
  std::string asset_dir;
  // Directory of the exported MJCF file. When set, mesh and terrain files
  // are named relative to it (MuJoCo resolves them against the model
  // file), and a decoded terrain image is written there unless asset_dir
  // says otherwise.
  std::string file_dir;
  // MuJoCo rangefinder sensors for the distance sensors (export: viewers
  // and mujoco-simulate show them). Physics leaves them out: it casts its
  // own rays, which also skip the sensor's own force plate.
  bool rangefinders = true;
  // true (what Physics uses): embedded meshes (embedded_mesh.h) are named
  // by file name only and handed back in MjcfInfo::memory_files for
  // MuJoCo's virtual file system; false: written as files like terrain.
  bool assets_in_memory = false;
  // Locks ("<robot>/<lock name>", see MjcfLock) to model as weld equality
  // constraints even where they could be rigid tree links, so they can be
  // released at run time (Physics::SetLockAttached).
  std::set<std::string> weld_locks;
  // The skybox and floor textures (4.7 MB in each mjModel). Worlds of a
  // split scene leave them out: only the scene's view model is drawn.
  bool textures = true;
  // Scene objects (by index) left out; the others keep their names. A
  // world of a split scene (world_split.h) holds only its own objects.
  std::vector<bool> skip_scene_objects;
};

// One lock of a robot as the model holds it.
struct MjcfLock {
  // Its guid, or a generated name when the guid is empty or shared:
  // "lock<k>" (k = index in Robot::locks) or "sm<k>/lock<j>" for the
  // implicit lock of sensor module k to its left (j = 0) or right (1)
  // neighbour.
  std::string name;
  // Name of its weld equality; empty when it is a rigid tree link.
  std::string weld;
  double break_force = 0;  // N; 0 never breaks
};

// What the builder made of the scenario, for Physics.
struct MjcfInfo {
  std::vector<std::vector<MjcfLock>> robot_locks;  // per scenario robot
  // The loose parts' locks (Scenario::loose_joints that are locks), so
  // that their break forces reach Physics as a robot's do.
  std::vector<MjcfLock> loose_locks;
  // Files the MJCF names that exist only in memory (assets_in_memory).
  std::vector<std::pair<std::string, std::vector<unsigned char>>> memory_files;
};

// Export form: equal to BuildMjcf(scenario, MjcfOptions{}).
std::string BuildMjcf(const Scenario& scenario);
// Throws ScenarioError (ValidateScenario, naming the element path) on
// anything the simulator cannot run, std::runtime_error when a mesh file
// vanished or the terrain image cannot be written.
std::string BuildMjcf(const Scenario& scenario, const MjcfOptions& options);
std::string BuildMjcf(const Scenario& scenario, const MjcfOptions& options,
                      MjcfInfo* info);

}  // namespace mrsim

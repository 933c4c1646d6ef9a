// Parts that overlap at the start (REQ-1.2.8): two robot parts, a part and
// a scene object, or anything and the terrain, interpenetrating in the
// pose the file gives. MuJoCo's own collision detection decides, on the
// model the simulator would run, so meshes, height fields and rotations
// count exactly as they will in the physics; parts joined by a hinge or a
// lock may touch (the model excludes them). A separate step from
// ValidateScenario, which never builds a model: `mrsim-scenario validate`
// and the studio call both.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "sim_core/scenario.h"
#include "sim_core/scenario_validate.h"

namespace mrsim {

// Deeper than this is an overlap; touching (a chain lying on the ground,
// parts face to face) is not.
inline constexpr double kOverlapTolerance = 0.001;  // m

struct PartOverlap {
  // What each part is ("robot 'snake' module 3 frame 0", "scene object 1",
  // "the terrain") and its element path in the file ("Scenario/robot[1]/
  // modules/Module[4]/frames/Frame[1]"), as validation errors name them.
  std::string first, second;
  std::string first_path, second_path;
  // The MJCF body names (mjcf_names.h), for tools that colour them.
  std::string first_body, second_body;
  double depth = 0;  // m, the deepest contact between the two
};

// Every pair overlapping deeper than `tolerance`, each pair once, deepest
// first. Throws std::runtime_error when the model cannot be built (the
// scenario should have been validated first).
std::vector<PartOverlap> FindOverlaps(const Scenario& scenario,
                                      double tolerance = kOverlapTolerance);

// The same on a model already built from `scenario` (the studio's
// preview): `model` must come from BuildMjcf of it (mjcf_names.h names).
// Throws std::runtime_error when MuJoCo data cannot be allocated.
std::vector<PartOverlap> FindOverlapsInModel(
    const Scenario& scenario, const mjModel* model,
    double tolerance = kOverlapTolerance);

// "file:line: path: robot 'snake' module 3 frame 0 overlaps scene object 1
// by 12.5 mm", the line and path those of the first part (without a
// source: "path: ...").
std::string DescribeOverlap(const PartOverlap& overlap,
                            const ScenarioSource* source = nullptr);

}  // namespace mrsim

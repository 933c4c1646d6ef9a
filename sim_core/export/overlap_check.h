// Parts that overlap at the start (REQ-1.2.8): two robot parts, a part and
// a scene object, or anything and the terrain, interpenetrating in the
// pose the file gives. MuJoCo's own collision detection decides, on the
// model the simulator would run, so meshes, height fields and rotations
// count exactly as they will in the physics; parts joined by a hinge or a
// lock may touch (the model excludes them). A separate step from
// ValidateScenario, which never builds a model: `mrsim-scenario validate`,
// mrsim-sim, `mrsim run`, the optimiser's body genes and the studio call
// both (RefuseOverlaps, or FindOverlaps to show them).
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <utility>
#include <vector>

#include "sim_core/scenario/scenario.h"
#include "sim_core/scenario/scenario_validate.h"

namespace mrsim {

// Deeper than this is an overlap; touching (a chain lying on the ground,
// parts face to face) is not.
inline constexpr double kOverlapTolerance = 0.001;  // m

struct PartOverlap {
  // What each part is, by the names the user gave ("robot 'snake' module 3
  // front frame", "scene object 'ball'" by its guid, "scene object 1" when its
  // guid is a generated GUID, "the terrain") and its element path in
  // the file ("Scenario/robot[1]/modules/Module[4]/frames/Frame[1]"), as
  // validation errors name them.
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

// "file:line: path: robot 'snake' module 3 front frame overlaps scene object 1
// by 12.5 mm", the line and path those of the first part (without a
// source: "path: ...").
std::string DescribeOverlap(const PartOverlap& overlap,
                            const ScenarioSource* source = nullptr);

// Parts overlapping at the start, refused: what() is one DescribeOverlap
// line per pair, deepest first; overlaps() the pairs themselves.
class OverlapError : public ScenarioError {
 public:
  OverlapError(std::string what, std::vector<PartOverlap> overlaps)
      : ScenarioError(std::move(what)), overlaps_(std::move(overlaps)) {}
  const std::vector<PartOverlap>& overlaps() const { return overlaps_; }

 private:
  std::vector<PartOverlap> overlaps_;
};

// What a program that refuses overlaps adds to OverlapError's lines (the
// flag of mrsim-sim and `mrsim run`; the studio's checkbox has its words).
inline constexpr char kAllowOverlapHint[] =
    "parts must not overlap at the start: move them apart, or allow "
    "overlap (--allow-overlap) to run it anyway";

// Throws OverlapError when any parts of `scenario` overlap at the start
// (FindOverlaps), naming each pair and how deep; std::runtime_error when
// the model cannot be built.
void RefuseOverlaps(const Scenario& scenario,
                    const ScenarioSource* source = nullptr);
// The same on a model already built from `scenario` (a simulator's, so
// the check costs no second compile; see FindOverlapsInModel).
void RefuseOverlapsInModel(const Scenario& scenario, const mjModel* model,
                           const ScenarioSource* source = nullptr);

}  // namespace mrsim

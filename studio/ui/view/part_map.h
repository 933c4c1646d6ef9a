// Which scenario part each geom of the compiled preview model shows, found
// through the MJCF names (sim_core/mjcf/mjcf_names.h), so a click in the 3-D
// view selects the part and the selection glows.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "sim_core/scenario/scenario.h"
#include "studio/design/selection.h"

namespace mrsim::studio {

enum class Look {
  kOther,
  kPitchModule,
  kYawModule,
  kSensorModule,
  kForcePlate,
  kDistanceSensor,
  kObject,
  kTerrain
};

struct GeomPart {
  Selection part;  // kNone for geoms of no part
  Look look = Look::kOther;
};

// One entry per geom of `model`, built from `scenario`.
std::vector<GeomPart> MapGeoms(const mjModel* model, const Scenario& scenario);

// A distance sensor's ray as drawn: from the site along its x axis.
struct RaySite {
  int site = -1;
  double length = 0;
  Selection part;
};
std::vector<RaySite> MapRays(const mjModel* model, const Scenario& scenario);

// A robot's lock as drawn and picked: a small marker between the bodies
// of the two parts it joins (locks have no geom of their own).
struct LockSite {
  int body_a = -1;
  int body_b = -1;
  Selection part;  // SelectionKind::kLock
  // How far above the middle of the two bodies the marker sits: on top of
  // the parts, which would hide a marker where they meet.
  double lift = 0.03;
};
std::vector<LockSite> MapLocks(const mjModel* model, const Scenario& scenario);

}  // namespace mrsim::studio

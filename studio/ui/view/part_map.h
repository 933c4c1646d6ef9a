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

}  // namespace mrsim::studio

// A named gait: a parameter set plus the kind of motion it drives (what a
// preset or a gait file holds).
#pragma once

#include <string>

#include "gait_controller/gait_parameters.h"
#include "gait_controller/motion.h"

namespace mrsim {

struct Gait {
  std::string name;
  GaitKind kind = GaitKind::kLinear;
  GaitParameters parameters;
};

bool operator==(const Gait& a, const Gait& b);
inline bool operator!=(const Gait& a, const Gait& b) { return !(a == b); }

}  // namespace mrsim

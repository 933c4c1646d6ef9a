#include "gait_controller/cpg_parameters.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace mrsim {

bool operator==(const CpgParameters& a, const CpgParameters& b) {
  return a.coupling == b.coupling && a.convergence == b.convergence &&
         a.feedback_gain == b.feedback_gain && a.force_scale == b.force_scale &&
         a.distance_range == b.distance_range;
}

namespace {

void Check(const char* field, double v, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi) {
    throw std::invalid_argument(fmt::format(
        "cpg {}: expected a number in [{}, {}], got {}", field, lo, hi, v));
  }
}

void CheckPositive(const char* field, double v) {
  if (!std::isfinite(v) || v <= 0) {
    throw std::invalid_argument(
        fmt::format("cpg {}: expected a number > 0, got {}", field, v));
  }
}

}  // namespace

void ValidateCpgParameters(const CpgParameters& p) {
  Check("coupling", p.coupling, 0.0, kMaxCpgCoupling);
  Check("convergence", p.convergence, kMinCpgConvergence, kMaxCpgConvergence);
  Check("feedback", p.feedback_gain, -kMaxCpgFeedbackGain, kMaxCpgFeedbackGain);
  CheckPositive("force_scale", p.force_scale);
  CheckPositive("distance_range", p.distance_range);
}

}  // namespace mrsim

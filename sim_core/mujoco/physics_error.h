// The error every unstable or failed MuJoCo step reports. It lives in the
// lowest room so that MuJoCo's callbacks (mujoco_handlers.h) can throw it
// without reaching up into the physics that steps.
#pragma once

#include <stdexcept>

namespace mrsim {

// Thrown when the simulation becomes unstable (NaN, MuJoCo warning).
class PhysicsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mrsim

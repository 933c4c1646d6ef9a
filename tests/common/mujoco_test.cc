#include "tests/common/mujoco_test.h"

#include <mujoco/mujoco.h>

#include <atomic>
#include <mutex>

#include "sim_core/mujoco/mujoco_handlers.h"

namespace mrsim::testing {
namespace {

std::atomic<int> expecting{0};
std::atomic<long> seen{0};

void OnWarning(const char* message) {
  seen.fetch_add(1);
  if (expecting.load() == 0) {
    ADD_FAILURE() << "unexpected MuJoCo warning: " << message;
  }
}

}  // namespace

void InstallMujocoWarningGuard() {
  static std::once_flag once;
  std::call_once(once, [] {
    // Ours first, so the library keeps this warning callback (it keeps
    // callbacks set before it) and errors still throw MujocoError.
    mju_user_warning = OnWarning;
    InstallMujocoHandlers();
  });
}

ExpectMujocoWarnings::ExpectMujocoWarnings() : start_(seen.load()) {
  InstallMujocoWarningGuard();
  expecting.fetch_add(1);
}

ExpectMujocoWarnings::~ExpectMujocoWarnings() { expecting.fetch_sub(1); }

long ExpectMujocoWarnings::count() const { return seen.load() - start_; }

}  // namespace mrsim::testing

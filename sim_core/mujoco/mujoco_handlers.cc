#include "sim_core/mujoco/mujoco_handlers.h"

#include <mujoco/mujoco.h>

#include <atomic>
#include <mutex>

namespace mrsim {
namespace {

std::atomic<long> warning_count{0};
std::mutex last_warning_mutex;
std::string& LastWarning() {
  static std::string* last = new std::string;  // outlives static destructors
  return *last;
}

// MuJoCo requires that the error callback does not return. The Debian
// build of libmujoco has unwind tables (.eh_frame), so a C++ exception
// unwinds through its C frames; tests/mujoco_handlers checks it.
[[noreturn]] void OnError(const char* message) {
  throw MujocoError(std::string("MuJoCo error: ") + message);
}

void OnWarning(const char* message) {
  {
    std::lock_guard<std::mutex> lock(last_warning_mutex);
    LastWarning() = message;
  }
  warning_count.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (mju_user_error == nullptr) mju_user_error = OnError;
    if (mju_user_warning == nullptr) mju_user_warning = OnWarning;
  });
}

long MujocoWarningCount() {
  return warning_count.load(std::memory_order_relaxed);
}

std::string LastMujocoWarning() {
  std::lock_guard<std::mutex> lock(last_warning_mutex);
  return LastWarning();
}

}  // namespace mrsim

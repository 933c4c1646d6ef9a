// The scenario reader and the one validator on any bytes, and, for what
// validates, the MJCF build through MuJoCo's compile: a file is refused with
// a ScenarioError or it compiles. fuzz-dict: xml
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_handlers.h"
#include "sim_core/scenario/scenario_xml.h"

namespace {

// Files beside the input never exist: paths in it resolve here.
constexpr char kNoDir[] = "/nonexistent-mrsim-fuzz";

bool Read(const std::string& xml, const mrsim::ScenarioReadOptions& options,
          mrsim::Scenario* out, std::string* error) {
  try {
    *out = mrsim::ReadScenarioString(xml, "fuzz.xml", kNoDir, options);
    return true;
  } catch (const mrsim::ScenarioError& e) {
    *error = e.what();
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool kHandlers = (mrsim::InstallMujocoHandlers(), true);
  (void)kHandlers;
  const std::string xml(reinterpret_cast<const char*>(data), size);
  mrsim::Scenario scenario;
  std::string error;
  if (!Read(xml, {}, &scenario, &error)) {
    // A file the original MRSim wrote: read it as `convert` does.
    if (error.find("--from unity-y-up") == std::string::npos ||
        !Read(xml, mrsim::kOriginalMrsimReadOptions, &scenario, &error)) {
      return 0;
    }
  }
  // What validates must build and compile (the validator is the one gate).
  try {
    mrsim::CompileScenarioModel(scenario, {});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "validated but did not compile: %s\n", e.what());
    std::abort();
  }
  return 0;
}

// The problem payload decoder on any bytes, as a farm worker decodes what a
// master sends (problem_codec.h): a problem, or a ProblemError. A Lua
// controller's script then loads in the sandbox and declares its
// parameters, as a worker's episode would, or fails with a LuaScriptError.
#include <cstdint>
#include <string>
#include <vector>

#include "lua_controller/lua_script.h"
#include "optimizer/episode/problem_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string payload(reinterpret_cast<const char*>(data), size);
  try {
    const mrsim::Problem p = mrsim::DecodeProblem(payload, "fuzz payload");
    p.genome.Check(p.genome.StartGenome());
    if (p.controller.kind == mrsim::ControllerSpec::Kind::kLua) {
      try {
        mrsim::LuaScript script(p.controller.source, p.controller.name);
        std::vector<double> values;
        for (const mrsim::LuaParameter& q : script.parameters()) {
          values.push_back(q.start);
        }
        script.SetParameters(values);
      } catch (const mrsim::LuaScriptError&) {
      }
    }
  } catch (const mrsim::ProblemError&) {
  }
  return 0;
}

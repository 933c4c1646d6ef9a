#include "optimizer/episode/controller_genes.h"

#include <algorithm>

#include "lua_controller/lua_script.h"
#include "optimizer/episode/mlp_genes.h"

namespace mrsim {

bool IsGaitGene(const std::string& name) {
  const auto& gait = GaitGeneNames();
  const auto& cpg = CpgGeneNames();
  return std::find(gait.begin(), gait.end(), name) != gait.end() ||
         std::find(cpg.begin(), cpg.end(), name) != cpg.end();
}

namespace {

bool IsBodyGene(const std::string& name) {
  const auto& body = BodyGeneNames();
  return std::find(body.begin(), body.end(), name) != body.end();
}

GenomeSpec LuaGenome(const ControllerSpec& controller, const GenomeSpec* user) {
  std::vector<LuaParameter> declared;
  try {
    // Its top level runs once, in the sandbox, to read `params`.
    declared = LuaScript(controller.source, controller.name).parameters();
  } catch (const LuaScriptError& e) {
    throw GenomeError(e.what());
  }
  if (declared.empty()) {
    throw GenomeError(controller.name +
                      ": declares no parameters (a global `params`, an array "
                      "of {name = ..., min = ..., max = ..., start = ...}; "
                      "docs/optimizer.md)");
  }
  GenomeSpec spec;
  for (const LuaParameter& p : declared) {
    if (IsGaitGene(p.name) || IsBodyGene(p.name)) {
      throw GenomeError(controller.name + ": parameter '" + p.name +
                        "' has the name of a built-in gene; rename it");
    }
    spec.genes.push_back({p.name, p.min, p.max, p.start, true, false});
  }
  if (user != nullptr) {
    spec.robot = user->robot;
    for (const GeneSpec& g : user->genes) {
      if (!IsBodyGene(g.name)) {
        throw GenomeError("--genome: gene '" + g.name +
                          "' is not a body gene; with --controller lua the "
                          "script's parameters are the controller's genes");
      }
      spec.genes.push_back(g);
    }
  }
  spec.Validate(controller.name);
  return spec;
}

}  // namespace

GenomeSpec ControllerGenome(const ControllerSpec& controller,
                            const GenomeSpec* user) {
  switch (controller.kind) {
    case ControllerSpec::Kind::kGait:
      if (user == nullptr) {
        throw GenomeError(
            "the gait controller needs --genome FILE or --genes sine|cpg");
      }
      return *user;
    case ControllerSpec::Kind::kLua:
      return LuaGenome(controller, user);
    case ControllerSpec::Kind::kMlp:
      return MlpGenome(controller, user);
  }
  throw GenomeError("unknown controller kind");
}

}  // namespace mrsim

// The genome a controller brings: for the gait, the genome the user gave
// (--genome/--genes); for a Lua script, its declared parameters (in
// declaration order, LuaParameter's min/max/start) followed by the body
// genes the user's genome adds (docs/optimizer.md).
#pragma once

#include <vector>

#include "optimizer/episode/controller_spec.h"
#include "optimizer/search/genome.h"

namespace mrsim {

// `user`: the genome of --genome/--genes (nullptr: none given). The gait
// needs one; a Lua script takes only body genes from it. Throws
// GenomeError naming the gene or the script's declaration that is wrong
// (LuaScriptError's message for a script that does not load).
GenomeSpec ControllerGenome(const ControllerSpec& controller,
                            const GenomeSpec* user);

// Whether `name` is a gene of the built-in gait (gait or CPG genes).
bool IsGaitGene(const std::string& name);

}  // namespace mrsim

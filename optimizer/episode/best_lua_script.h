// The best individual of a Lua run as a script mrsim-lua runs: the user's
// script with a block appended that sets each declared parameter's start
// to the best value found (so P holds those values, exactly, when it
// runs), and a header comment saying where it came from.
#pragma once

#include <string>

#include "optimizer/episode/controller_spec.h"
#include "optimizer/search/genome.h"

namespace mrsim {

// `spec`/`best`: the run's genome and its best values; genes that are not
// the script's parameters (body genes) are left out.
std::string BestLuaScript(const ControllerSpec& controller,
                          const GenomeSpec& spec, const Genome& best);

}  // namespace mrsim

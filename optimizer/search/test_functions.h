// Cheap known functions to exercise the algorithms without physics:
// fitness = -f(x), so the optimum 0 is at the origin.
#pragma once

#include <string>

#include "optimizer/search/eval_result.h"
#include "optimizer/search/genome.h"

namespace mrsim {

// "sphere" (sum x^2) or "rastrigin" (10 n + sum x^2 - 10 cos(2 pi x)).
// Throws std::invalid_argument on another name.
EvalResult EvaluateTestFunction(const std::string& name, const Genome& x);

// A spec of n genes "x0".."x{n-1}" in [lower, upper], start at `start`.
GenomeSpec TestFunctionSpec(int n, double lower, double upper, double start);

}  // namespace mrsim

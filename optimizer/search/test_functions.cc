#include "optimizer/search/test_functions.h"

#include <cmath>
#include <stdexcept>

namespace mrsim {

EvalResult EvaluateTestFunction(const std::string& name, const Genome& x) {
  double f = 0;
  if (name == "sphere") {
    for (double v : x) f += v * v;
  } else if (name == "rastrigin") {
    f = 10.0 * x.size();
    for (double v : x) f += v * v - 10.0 * std::cos(2.0 * M_PI * v);
  } else {
    throw std::invalid_argument("unknown test function '" + name +
                                "' (expected sphere or rastrigin)");
  }
  EvalResult r;
  r.fitness = -f;
  return r;
}

GenomeSpec TestFunctionSpec(int n, double lower, double upper, double start) {
  GenomeSpec spec;
  for (int i = 0; i < n; ++i) {
    GeneSpec g;
    g.name = "x" + std::to_string(i);
    g.lower = lower;
    g.upper = upper;
    g.start = start;
    spec.genes.push_back(g);
  }
  spec.Validate("test function");
  return spec;
}

}  // namespace mrsim

// Evaluates a whole generation at once, so a thread pool or a farm of
// worker processes can run it in parallel.
#pragma once

#include <stdexcept>
#include <vector>

#include "optimizer/eval_result.h"
#include "optimizer/genome.h"

namespace mrsim {

// Thrown by an evaluator when a stop was requested (SIGINT/SIGTERM) in the
// middle of a batch; the batch is abandoned.
class EvaluationInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class BatchEvaluator {
 public:
  virtual ~BatchEvaluator() = default;
  // One result per genome, in the same order. The result of a genome must
  // depend on the genome alone (not on order, timing or who computes it).
  virtual std::vector<EvalResult> Evaluate(
      const std::vector<Genome>& batch) = 0;
  // For progress lines: how many threads or workers are evaluating.
  virtual int workers_alive() const { return 1; }
};

}  // namespace mrsim

// Evaluates a batch on a pool of threads of this process. Each call of the
// function must be independent (an episode builds its own Physics), so the
// result of a genome never depends on which thread ran it.
#pragma once

#include <functional>
#include <vector>

#include "optimizer/search/batch_evaluator.h"

namespace mrsim {

class LocalEvaluator : public BatchEvaluator {
 public:
  using Function = std::function<EvalResult(const Genome&)>;
  // `stop` (optional) is polled between evaluations; when it returns true
  // the batch is abandoned with EvaluationInterrupted.
  LocalEvaluator(Function function, int threads,
                 std::function<bool()> stop = nullptr);

  std::vector<EvalResult> Evaluate(const std::vector<Genome>& batch) override;
  int workers_alive() const override { return threads_; }

 private:
  Function function_;
  int threads_;
  std::function<bool()> stop_;
};

}  // namespace mrsim

// Evaluates a whole generation at once, so a thread pool or a farm of
// worker processes can run it in parallel.
#pragma once

#include <deque>
#include <stdexcept>
#include <utility>
#include <vector>

#include "optimizer/search/eval_result.h"
#include "optimizer/search/genome.h"

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

  // Starts a batch without waiting for it; Collect returns the oldest
  // batch not yet collected, once it is done. A farm hands out the next
  // batch's jobs while the last episodes of one run, so no worker waits for
  // a generation's slowest episode. This default evaluates every batch
  // submitted so far as one when the oldest is collected (a thread pool
  // then waits once for two generations). Not to be mixed with Evaluate
  // while batches are in flight.
  virtual void Submit(std::vector<Genome> batch) {
    submitted_.push_back(std::move(batch));
  }
  virtual std::vector<EvalResult> Collect() {
    if (collected_.empty()) {
      if (submitted_.empty()) {
        throw std::logic_error("Collect: nothing submitted");
      }
      std::vector<Genome> all;
      for (const std::vector<Genome>& b : submitted_) {
        all.insert(all.end(), b.begin(), b.end());
      }
      const std::vector<EvalResult> results = Evaluate(all);
      if (results.size() != all.size()) return results;  // caller reports
      auto next = results.begin();
      for (const std::vector<Genome>& b : submitted_) {
        collected_.emplace_back(next, next + static_cast<long>(b.size()));
        next += static_cast<long>(b.size());
      }
      submitted_.clear();
    }
    std::vector<EvalResult> oldest = std::move(collected_.front());
    collected_.pop_front();
    return oldest;
  }

 private:
  std::deque<std::vector<Genome>> submitted_;
  std::deque<std::vector<EvalResult>> collected_;
};

}  // namespace mrsim

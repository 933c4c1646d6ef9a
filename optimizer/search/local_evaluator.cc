#include "optimizer/search/local_evaluator.h"

#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace mrsim {

LocalEvaluator::LocalEvaluator(Function function, int threads,
                               std::function<bool()> stop)
    : function_(std::move(function)),
      threads_(threads),
      stop_(std::move(stop)) {
  if (threads_ < 1) {
    throw std::invalid_argument("local evaluator: threads must be >= 1");
  }
}

std::vector<EvalResult> LocalEvaluator::Evaluate(
    const std::vector<Genome>& batch) {
  std::vector<EvalResult> results(batch.size());
  std::atomic<size_t> next{0};
  std::atomic<bool> stopped{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&]() {
    for (;;) {
      if (stop_ && stop_()) {
        stopped = true;
        return;
      }
      const size_t i = next.fetch_add(1);
      if (i >= batch.size()) return;
      try {
        results[i] = function_(batch[i]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = batch.size();
        return;
      }
    }
  };
  const int n = std::min<int>(threads_, static_cast<int>(batch.size()));
  if (n <= 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < n; ++t) pool.emplace_back(work);
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
  if (stopped) throw EvaluationInterrupted("evaluation interrupted");
  return results;
}

}  // namespace mrsim

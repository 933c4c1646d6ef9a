#include "optimizer/process/opt_progress_reporter.h"

#include <filesystem>
#include <utility>

#include "optimizer/process/opt_command.h"

namespace mrsim {

OptProgressReporter::OptProgressReporter(std::string run_id,
                                         const std::string& out_dir,
                                         std::string algorithm) {
  last_.run_id = std::move(run_id);
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(out_dir, ec);
  last_.out_dir = ec ? out_dir : absolute.lexically_normal().string();
  last_.algorithm = std::move(algorithm);
  last_.island = -1;
  last_.eta_seconds = -1;
  last_.eta = FormatDuration(-1);
  last_.state = opt_progress_t::RUNNING;
}

opt_progress_t OptProgressReporter::Stamp(int64_t utime) {
  last_.utime = utime;
  last_.seq = ++seq_;
  return last_;
}

opt_progress_t OptProgressReporter::Generation(const GenerationReport& r,
                                               int64_t utime) {
  last_.generation = r.generation;
  last_.generations = r.generations;
  last_.island = r.island;
  last_.best = r.best;
  last_.mean = r.mean;
  last_.best_so_far = r.best_so_far;
  last_.failed = r.failed;
  last_.evaluations = r.evaluations;
  last_.evals_per_second = r.evals_per_second;
  last_.workers = r.workers;
  last_.eta_seconds = r.eta_seconds;
  last_.eta = FormatDuration(r.eta_seconds);
  last_.replayed = r.replayed;
  last_.state = opt_progress_t::RUNNING;
  last_.error.clear();
  return Stamp(utime);
}

opt_progress_t OptProgressReporter::End(int8_t state, int64_t utime,
                                        const std::string& error) {
  last_.state = state;
  last_.error = error;
  if (state == opt_progress_t::FINISHED) {
    last_.eta_seconds = 0;
    last_.eta = FormatDuration(0);
  }
  return Stamp(utime);
}

}  // namespace mrsim

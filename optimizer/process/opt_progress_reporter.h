// mrsim-opt's progress as messages: turns each generation's report into an
// opt_progress_t (and the end of the run into a last one) for whoever
// publishes it. The core of --progress-url: no LCM here, main owns the
// connection; tests drive it with reports and a fake time.
#pragma once

#include <cstdint>
#include <string>

#include "mrsim/opt_progress_t.hpp"
#include "optimizer/search/optimization_run.h"

namespace mrsim {

class OptProgressReporter {
 public:
  // out_dir is sent as an absolute path; algorithm as its word. utime:
  // the wall clock in microseconds (WallMicros()).
  OptProgressReporter(std::string run_id, const std::string& out_dir,
                      std::string algorithm);

  // The message for a completed generation (state RUNNING).
  opt_progress_t Generation(const GenerationReport& report, int64_t utime);
  // The last message: `state` FINISHED, STOPPED or FAILED (with `error`),
  // carrying the last generation's figures.
  opt_progress_t End(int8_t state, int64_t utime,
                     const std::string& error = "");

 private:
  opt_progress_t Stamp(int64_t utime);

  opt_progress_t last_{};
  int64_t seq_ = 0;
};

}  // namespace mrsim

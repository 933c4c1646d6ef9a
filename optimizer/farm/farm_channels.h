// Channel names of the optimiser farm: <prefix>_RUN, _CHUNK,
// _CHUNK_REQUEST, _HEARTBEAT, _JOB, _RESULT (default prefix MRSIM_OPT),
// and mrsim-opt's progress, <prefix>_PROGRESS (opt_progress_t).
#pragma once

#include <string>

namespace mrsim {

inline constexpr const char* kDefaultFarmPrefix = "MRSIM_OPT";

struct FarmChannels {
  explicit FarmChannels(const std::string& prefix)
      : run(prefix + "_RUN"),
        chunk(prefix + "_CHUNK"),
        chunk_request(prefix + "_CHUNK_REQUEST"),
        heartbeat(prefix + "_HEARTBEAT"),
        job(prefix + "_JOB"),
        result(prefix + "_RESULT"),
        progress(prefix + "_PROGRESS") {}
  std::string run, chunk, chunk_request, heartbeat, job, result, progress;
};

}  // namespace mrsim

// Channel names of the optimiser farm: <prefix>_RUN, _CHUNK,
// _CHUNK_REQUEST, _HEARTBEAT, _RESULT (default prefix MRSIM_OPT),
// mrsim-opt's progress <prefix>_PROGRESS (opt_progress_t), and the jobs on
// kJobShards channels _JOB_00 .. _JOB_ff, a worker's jobs on the one its id
// hashes to: a worker subscribes to its own shard only, so a tcpq hub copies
// each job to about W/256 workers instead of all W, and mpudpm spreads the jobs
// over its ports (docs/scaling.md).
#pragma once

#include <cstdio>
#include <string>

#include "common/hash.h"

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

  // "<prefix>_JOB_" and the shard in two hex digits.
  std::string JobChannel(int shard) const {
    char hex[8];
    std::snprintf(hex, sizeof hex, "_%02x", shard & 0xff);
    return job + hex;
  }
};

inline constexpr int kJobShards = 256;

// The job shard of a worker id.
inline int JobShard(const std::string& worker_id) {
  return static_cast<int>(Fnv1a64(worker_id) % kJobShards);
}

}  // namespace mrsim

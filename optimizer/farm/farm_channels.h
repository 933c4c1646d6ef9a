// Channel names of the optimiser farm, from the channel table the .lcm
// files declare (lcmtypes/runtime/channels.h): <prefix>_RUN, _CHUNK,
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
#include "lcmtypes/runtime/channels.h"

namespace mrsim {

inline constexpr const char* kDefaultFarmPrefix =
    ChannelNamed("run").default_prefix;

struct FarmChannels {
  explicit FarmChannels(const std::string& prefix)
      : run(ChannelName(ChannelNamed("run"), prefix)),
        chunk(ChannelName(ChannelNamed("chunk"), prefix)),
        chunk_request(ChannelName(ChannelNamed("chunk_request"), prefix)),
        heartbeat(ChannelName(ChannelNamed("heartbeat"), prefix)),
        result(ChannelName(ChannelNamed("result"), prefix)),
        progress(ChannelName(ChannelNamed("progress"), prefix)),
        prefix_(prefix) {}
  std::string run, chunk, chunk_request, heartbeat, result, progress;

  // "<prefix>_JOB_" and the shard in two hex digits.
  std::string JobChannel(int shard) const {
    char hex[4];
    std::snprintf(hex, sizeof hex, "%02x", shard & 0xff);
    return ChannelName(ChannelNamed("job"), prefix_, hex);
  }

 private:
  std::string prefix_;
};

inline constexpr int kJobShards = 256;

// The job shard of a worker id.
inline int JobShard(const std::string& worker_id) {
  return static_cast<int>(Fnv1a64(worker_id) % kJobShards);
}

}  // namespace mrsim

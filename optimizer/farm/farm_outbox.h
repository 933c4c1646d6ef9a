// What a farm node's core asks its adapter to publish: decoded messages, one
// list per channel, and whether to re-create the LCM connection.
#pragma once

#include <vector>

#include "mrsim/opt_chunk_request_t.hpp"
#include "mrsim/opt_chunk_t.hpp"
#include "mrsim/opt_heartbeat_t.hpp"
#include "mrsim/opt_job_t.hpp"
#include "mrsim/opt_result_t.hpp"
#include "mrsim/opt_run_t.hpp"

namespace mrsim {

struct FarmOutbox {
  std::vector<opt_run_t> runs;
  std::vector<opt_chunk_t> chunks;
  std::vector<opt_chunk_request_t> chunk_requests;
  std::vector<opt_heartbeat_t> heartbeats;
  std::vector<opt_job_t> jobs;
  std::vector<opt_result_t> results;
  // Re-create the connection: a worker that hears nothing any more may have
  // lost its multicast group membership (a link flap).
  bool rejoin = false;
  // Times to publish each job and each result (opt_run_t.copies): a second
  // copy makes one lost datagram cost nothing; receivers drop duplicates.
  int copies = 1;

  bool empty() const {
    return runs.empty() && chunks.empty() && chunk_requests.empty() &&
           heartbeats.empty() && jobs.empty() && results.empty() && !rejoin;
  }
};

}  // namespace mrsim

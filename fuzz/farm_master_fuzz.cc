// The farm master's core (FarmMasterCore) fed decodable but hostile
// heartbeats, results and chunk requests: unknown workers, other runs,
// results for jobs never sent or sent to someone else, absurd job ids,
// NaN and 1e308 fitness, chunk requests for chunks that do not exist,
// clock jumps. It must never crash, and every result it keeps must be for
// a job of the batch.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz/hostile_input.h"
#include "optimizer/farm/farm_master_core.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  fuzz::HostileInput in(data, size);
  FarmSettings settings;
  settings.chunk_size = 64;
  FarmMasterCore master(std::string(200, 'p'), "run", 1, settings);
  const std::string run = master.run_id();
  const std::string hash = master.scenario_hash();
  const std::vector<std::string> workers = {"w1", "w2"};
  const std::vector<Genome> batch(4, Genome{0.5, 1.0, 1.5});
  master.StartBatch(batch, 0.0);
  double now = 0;
  std::vector<opt_job_t> sent;
  for (int op = 0; op < 64 && !in.empty(); ++op) {
    switch (in.Byte() % 5) {
      case 0: {
        opt_heartbeat_t msg = in.Heartbeat(workers, run, hash);
        if (fuzz::ThroughWire(&msg)) master.OnHeartbeat(msg, now);
        break;
      }
      case 1: {
        opt_result_t msg = in.Result(workers, run, hash);
        if (!sent.empty() && in.Bool()) {  // answers a job really sent
          const opt_job_t& job = sent[in.Byte() % sent.size()];
          msg.job_id = job.job_id;
          msg.generation = job.generation;
          msg.index = job.index;
        }
        if (fuzz::ThroughWire(&msg)) master.OnResult(msg, now);
        break;
      }
      case 2: {
        opt_chunk_request_t msg = in.ChunkRequest(workers, run, hash);
        if (fuzz::ThroughWire(&msg)) master.OnChunkRequest(msg, now);
        break;
      }
      case 3:
        master.CountMalformed();
        break;
      default: {
        now += in.Step();
        FarmOutbox out = master.Tick(now);
        for (opt_job_t& job : out.jobs) sent.push_back(std::move(job));
        if (sent.size() > 64) sent.erase(sent.begin(), sent.end() - 64);
        break;
      }
    }
  }
  if (master.batch_done() && master.results().size() != batch.size()) {
    std::abort();  // a finished batch has one result per genome
  }
  return 0;
}

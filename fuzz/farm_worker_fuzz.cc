// The farm worker's core (FarmWorkerCore) fed decodable but hostile
// announcements, payload chunks and jobs: other runs, absurd chunk counts
// and payload sizes, chunks that disagree with the announcement, jobs for
// other workers, NaN and 1e308 genes, clock jumps. It must never crash nor
// hold more memory than the announced payload allows.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/hash.h"
#include "fuzz/hostile_input.h"
#include "optimizer/farm/farm_worker_core.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  static const std::string kPayload(100, 'p');
  static const std::string kHash = HashHex(Fnv1a64(kPayload));
  const std::string run = "run";
  fuzz::HostileInput in(data, size);
  WorkerSettings settings;
  settings.id = "w1";
  settings.fake_episode = 0.01;
  FarmWorkerCore worker(settings, "host", 1,
                        [](const std::string&, const std::string&) {
                          return std::make_shared<const Problem>();
                        });
  double now = 0;
  for (int op = 0; op < 64 && !in.empty(); ++op) {
    switch (in.Byte() % 5) {
      case 0: {
        opt_run_t msg = in.Run(run, kHash);
        if (in.Bool()) {  // the true announcement, hostile numbers aside
          msg.payload_size = static_cast<int64_t>(kPayload.size());
          msg.chunk_count = 2;
          msg.chunk_size = 64;
        }
        if (fuzz::ThroughWire(&msg)) worker.OnRun(msg, now);
        break;
      }
      case 1: {
        opt_chunk_t msg = in.Chunk(run, kHash);
        if (in.Bool()) {  // a true chunk of the payload
          msg.index = in.Bool() ? 1 : 0;
          msg.count = 2;
          const std::string part = kPayload.substr(msg.index * 64, 64);
          msg.data.assign(part.begin(), part.end());
          msg.size = static_cast<int32_t>(msg.data.size());
        }
        if (fuzz::ThroughWire(&msg)) worker.OnChunk(msg, now);
        break;
      }
      case 2: {
        opt_job_t msg = in.Job(run, kHash, "w1", 3);
        if (fuzz::ThroughWire(&msg)) worker.OnJob(msg, now);
        break;
      }
      case 3: {
        for (WorkerTask& task : worker.TakeTasks(in.Byte() % 3)) {
          opt_result_t result{};
          result.run_id = task.run_id;
          result.scenario_hash = task.hash;
          result.worker_id = "w1";
          result.job_id = task.job_id;
          result.fitness = in.Double();
          worker.OnEpisodeDone(result, now);
        }
        break;
      }
      default:
        now += in.Step();
        worker.Tick(now);
        break;
    }
    worker.TakeLog();
  }
  return 0;
}

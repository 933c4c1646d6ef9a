// The master's farm evaluator in this process, a real mrsim-worker process,
// and an intruder publishing answers of another run, of another payload,
// and garbage on the farm channels (LCM port 7702).
#include <gtest/gtest.h>

#include <atomic>
#include <lcm/lcm-cpp.hpp>
#include <thread>

#include "gait_controller/gait_presets.h"
#include "mrsim/opt_result_t.hpp"
#include "optimizer/episode/episode.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_evaluator.h"
#include "optimizer/episode/problem_codec.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"

namespace mrsim {
namespace {

TEST(FarmEvaluator, IgnoresOtherRunsOtherPayloadsAndGarbage) {
  const std::string url = testing::TestLcmUrl(7702);
  Problem p;
  p.scenario = ReadScenarioFile(testing::SourcePath("scenarios/snake11.xml"));
  p.genome =
      ReadGenomeFile(testing::SourcePath("scenarios/forward_gait.genome.xml"));
  p.episode.duration = 1.0;
  p.episode.base_gait = *FindGaitPreset("forward");
  const std::string payload = EncodeProblem(p);
  const Problem problem = DecodeProblem(payload, "test");

  const std::string dir = testing::TempDir("farm_messages");
  testing::ChildProcess worker(
      {testing::BinaryPath("optimizer/process/mrsim-worker"), "--lcm-url", url,
       "--id", "honest"},
      dir + "/worker.log");
  SignedLcm lcm(url);
  ASSERT_TRUE(lcm.good());
  FarmSettings settings;
  // The honest worker must not be dropped because a loaded machine left it
  // unscheduled for a while; this test is about foreign messages.
  settings.worker_timeout = 10.0;
  FarmEvaluator farm(lcm, payload, "run-under-test", settings);

  std::atomic<bool> done{false};
  std::thread intruder([&] {
    lcm::LCM other(url);
    const FarmChannels ch(kDefaultFarmPrefix);
    const unsigned char garbage[] = {1, 2, 3, 4, 5, 6, 7};
    // Noise every 10 ms for as long as the batch runs.
    testing::RepeatUntil(
        [&] {
          for (int i = 0; i < 4; ++i) {
            opt_result_t r{};
            r.job_id = (1ll << 24) | i;  // the first batch's job ids
            r.fitness = 1e9;
            r.worker_id = "intruder";
            r.run_id = "another-run";
            r.scenario_hash = farm.scenario_hash();
            other.publish(ch.result, &r);
            r.run_id = "run-under-test";
            r.scenario_hash = "0123456789abcdef";
            other.publish(ch.result, &r);
          }
          other.publish(ch.result, garbage, sizeof garbage);
          other.publish(ch.heartbeat, garbage, sizeof garbage);
        },
        [&] { return done.load(); }, 0.01, 600);
  });
  Random random(4);
  std::vector<Genome> batch;
  for (int i = 0; i < 4; ++i)
    batch.push_back(problem.genome.RandomGenome(random));
  const std::vector<EvalResult> results = farm.Evaluate(batch);
  done = true;
  intruder.join();
  ASSERT_EQ(results.size(), 4u);
  for (size_t i = 0; i < batch.size(); ++i) {
    EXPECT_EQ(results[i].fitness, RunEpisode(problem, batch[i]).fitness);
  }
  EXPECT_GT(farm.counters().results_ignored, 0);
  EXPECT_GT(farm.counters().messages_malformed, 0);
  EXPECT_EQ(farm.workers_alive(), 1);
}

}  // namespace
}  // namespace mrsim

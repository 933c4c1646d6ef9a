// mrsim-opt's progress messages from generation reports and the end of a
// run, without LCM: what a studio or a script listening on
// MRSIM_OPT_PROGRESS reads.
#include "optimizer/process/opt_progress_reporter.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "lcmtypes/runtime/decode.h"
#include "optimizer/farm/farm_channels.h"

namespace mrsim {
namespace {

GenerationReport Report(int generation) {
  GenerationReport r;
  r.generation = generation;
  r.generations = 20;
  r.best = 0.5;
  r.mean = 0.25;
  r.best_so_far = 0.75;
  r.failed = 1;
  r.evaluations = 8 * generation;
  r.evals_per_second = 5.2;
  r.workers = 2;
  r.eta_seconds = 72;
  return r;
}

TEST(OptProgressReporter, GenerationMessageCarriesWhatTheHumanLineSays) {
  OptProgressReporter reporter("run-1", "out/opt", "cmaes");
  const opt_progress_t m = reporter.Generation(Report(3), 1'000'000);
  EXPECT_EQ(m.utime, 1'000'000);
  EXPECT_EQ(m.seq, 1);
  EXPECT_EQ(m.run_id, "run-1");
  EXPECT_EQ(m.out_dir,
            std::filesystem::absolute("out/opt").lexically_normal().string());
  EXPECT_EQ(m.algorithm, "cmaes");
  EXPECT_EQ(m.generation, 3);
  EXPECT_EQ(m.generations, 20);
  EXPECT_EQ(m.island, -1);
  EXPECT_EQ(m.best, 0.5);
  EXPECT_EQ(m.mean, 0.25);
  EXPECT_EQ(m.best_so_far, 0.75);
  EXPECT_EQ(m.failed, 1);
  EXPECT_EQ(m.evaluations, 24);
  EXPECT_EQ(m.evals_per_second, 5.2);
  EXPECT_EQ(m.workers, 2);
  EXPECT_EQ(m.eta_seconds, 72);
  EXPECT_EQ(m.eta, "1m12s");
  EXPECT_EQ(m.state, int{opt_progress_t::RUNNING});
}

TEST(OptProgressReporter, EndMessagesSayHowTheRunEndedWithItsLastFigures) {
  OptProgressReporter reporter("run-1", "/tmp/o", "ga");
  reporter.Generation(Report(20), 1);
  const opt_progress_t done = reporter.End(opt_progress_t::FINISHED, 2);
  EXPECT_EQ(done.seq, 2);
  EXPECT_EQ(done.state, int{opt_progress_t::FINISHED});
  EXPECT_EQ(done.generation, 20);
  EXPECT_EQ(done.eta, "0s");
  const opt_progress_t failed =
      reporter.End(opt_progress_t::FAILED, 3, "checkpoint of other settings");
  EXPECT_EQ(failed.state, int{opt_progress_t::FAILED});
  EXPECT_EQ(failed.error, "checkpoint of other settings");
}

TEST(OptProgressReporter,
     UnknownEtaBeforeARateAndTheMessagePassesTheWireCheck) {
  OptProgressReporter reporter("run-1", "/tmp/o", "ga");
  GenerationReport r = Report(1);
  r.eta_seconds = -1;
  r.replayed = true;
  const opt_progress_t m = reporter.Generation(r, 5);
  EXPECT_EQ(m.eta, "?");
  EXPECT_TRUE(m.replayed);
  std::vector<uint8_t> bytes(m.getEncodedSize());
  ASSERT_EQ(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  opt_progress_t back;
  ASSERT_TRUE(DecodeMessage(bytes.data(), bytes.size(), &back));
  EXPECT_EQ(back.out_dir, m.out_dir);
  EXPECT_EQ(FarmChannels("MRSIM_OPT").progress, "MRSIM_OPT_PROGRESS");
}

}  // namespace
}  // namespace mrsim

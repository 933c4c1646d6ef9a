#include "sim_core/mujoco/mujoco_handlers.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "optimizer/episode/episode.h"
#include "optimizer/search/local_evaluator.h"
#include "sim_core/physics/physics.h"
#include "tests/common/child_process.h"
#include "tests/common/mujoco_test.h"
#include "tests/mujoco_embedding/exploding_scenario.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;
using testing::ExpectMujocoWarnings;

// Each test runs in its own empty directory, where MuJoCo's defaults
// would write MUJOCO_LOG.TXT.
class MujocoEmbedding : public testing::MujocoTest {
 protected:
  void SetUp() override {
    dir_ = testing::TempDir(
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    old_ = fs::current_path();
    fs::current_path(dir_);
  }
  void TearDown() override {
    EXPECT_FALSE(fs::exists(fs::path(dir_) / "MUJOCO_LOG.TXT"));
    fs::current_path(old_);
  }
  std::string dir_;
  fs::path old_;
};

MjModelPtr LoadModel(const char* xml) {
  InstallMujocoHandlers();
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  mj_makeEmptyFileVFS(&vfs, "m.xml", static_cast<int>(std::strlen(xml)));
  std::memcpy(vfs.filedata[vfs.nfile - 1], xml, std::strlen(xml));
  char error[500] = "";
  MjModelPtr m(mj_loadXML("m.xml", &vfs, error, sizeof(error)));
  mj_deleteVFS(&vfs);
  EXPECT_TRUE(m) << error;
  return m;
}

constexpr char kTwoBalls[] =
    "<mujoco><worldbody><body><freejoint/><geom size='.1'/></body>"
    "<body pos='0 0 1'><freejoint/><geom size='.1'/></body></worldbody>"
    "</mujoco>";

TEST_F(MujocoEmbedding, ErrorInsideAStepIsAnExceptionAndTheProcessGoesOn) {
  MjModelPtr m = LoadModel(kTwoBalls);
  ASSERT_TRUE(m);
  m->nstack = 20;  // far too small: mj_step's stack allocation fails
  MjDataPtr d(mj_makeData(m.get()));
  ::testing::internal::CaptureStdout();
  try {
    mj_step(m.get(), d.get());
    FAIL() << "expected MujocoError";
  } catch (const MujocoError& e) {
    EXPECT_NE(std::string(e.what()).find("Stack overflow"), std::string::npos)
        << e.what();
  }
  // A PhysicsError: whoever handles an unstable step handles this too.
  EXPECT_THROW(mj_step(m.get(), d.get()), PhysicsError);
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
}

TEST_F(MujocoEmbedding, WarningIsCountedNotPrinted) {
  MjModelPtr m = LoadModel(kTwoBalls);
  ASSERT_TRUE(m);
  MjDataPtr d(mj_makeData(m.get()));
  ExpectMujocoWarnings expected;
  ::testing::internal::CaptureStdout();
  d->qvel[0] = NAN;
  mj_step(m.get(), d.get());
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(expected.count(), 1);
  EXPECT_EQ(d->warning[mjWARN_BADQVEL].number, 1);
}

TEST_F(MujocoEmbedding, ExplodingPhysicsRaisesPhysicsErrorSilently) {
  Physics physics(testing::ExplodingScenario());
  ExpectMujocoWarnings expected;
  ::testing::internal::CaptureStdout();
  EXPECT_THROW(physics.Step(200), PhysicsError);
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_GE(expected.count(), 1);
}

Problem ExplodingProblem() {
  Problem p;
  p.scenario = testing::ExplodingScenario();
  p.genome = ReadGenomeString(
      R"(<genome><gene name="A_pitch" lower="0" upper="1.5" start="1"/>
</genome>)",
      "test genome");
  p.episode.duration = 30;
  p.episode.control_period = 0.5;
  return p;
}

TEST_F(MujocoEmbedding, ExplodingEpisodeIsReportedFailed) {
  const Problem problem = ExplodingProblem();
  ExpectMujocoWarnings expected;
  ::testing::internal::CaptureStdout();
  const EvalResult r = RunEpisode(problem, problem.genome.StartGenome());
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.fitness, kFailedFitness);
}

TEST_F(MujocoEmbedding, LocalEvaluatorReportsExplodingEpisodesFailed) {
  const Problem problem = ExplodingProblem();
  ExpectMujocoWarnings expected;
  LocalEvaluator evaluator(
      [&](const Genome& g) { return RunEpisode(problem, g); }, 2);
  const Genome g = problem.genome.StartGenome();
  ::testing::internal::CaptureStdout();
  const std::vector<EvalResult> results = evaluator.Evaluate({g, g, g});
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  ASSERT_EQ(results.size(), 3u);
  for (const EvalResult& r : results) EXPECT_TRUE(r.failed);
}

TEST_F(MujocoEmbedding, HandlersSetByTheApplicationAreKept) {
  // The guard of this test binary was installed before the library's.
  InstallMujocoHandlers();
  EXPECT_NE(mju_user_warning, nullptr);
  ExpectMujocoWarnings expected;
  mju_warning("from the test");
  EXPECT_EQ(expected.count(), 1);
}

}  // namespace
}  // namespace mrsim

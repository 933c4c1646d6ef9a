#include "optimizer/episode/episode.h"

#include <gtest/gtest.h>

#include <thread>

#include "gait_controller/gait_presets.h"
#include "optimizer/episode/body_genes.h"
#include "optimizer/episode/episode_physics_pool.h"
#include "optimizer/episode/problem_codec.h"
#include "optimizer/search/local_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/optimizer/sim_farm.h"

namespace mrsim {
namespace {

Problem SnakeProblem(double seconds) {
  Problem p;
  p.scenario.robots.push_back(MakeChain(ChainOptions{}));
  p.genome = ReadGenomeString(R"(<genome>
  <gene name="A_pitch" lower="0" upper="1.5" start="1"/>
  <gene name="phi_pitch" lower="0" upper="3.14" start="2.5"/>
  <gene name="T" lower="1" upper="6" start="4"/>
</genome>)",
                              "test genome");
  p.episode.duration = seconds;
  p.episode.base_gait = *FindGaitPreset("forward");
  return p;
}

TEST(OptimizerEpisode, SameGenomeGivesTheSameFitnessBitForBit) {
  const Problem problem = SnakeProblem(2.0);
  const Genome g = problem.genome.StartGenome();
  const EvalResult a = RunEpisode(problem, g);
  EvalResult b;
  std::thread t([&] { b = RunEpisode(problem, g); });
  t.join();
  EXPECT_FALSE(a.failed);
  EXPECT_EQ(a.fitness, b.fitness);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_GT(a.energy, 0.0);
  // A different gait gives a different fitness.
  Genome other = g;
  other[0] = 0.5;
  EXPECT_NE(RunEpisode(problem, other).fitness, a.fitness);
}

// Episodes reuse a kept Physics (reset) when the body is unchanged, in
// whichever thread; an episode after others, in another thread, must
// equal one on a freshly built Physics, bit for bit, on scenes with
// terrain, sensor modules and force sensors too.
TEST(OptimizerEpisode, EpisodeAfterOthersEqualsAFreshOneBitForBit) {
  for (const char* path : {"scenarios/case_study.xml", "scenarios/terrain.xml",
                           "scenarios/snake11.xml"}) {
    Problem problem = SnakeProblem(1.5);
    problem.scenario = ReadScenarioFile(testing::SourcePath(path));
    EmbedAssets(problem.scenario);
    problem = DecodeProblem(EncodeProblem(problem), path);
    Random random(3);
    std::vector<Genome> genomes;
    for (int i = 0; i < 4; ++i) {
      genomes.push_back(problem.genome.RandomGenome(random));
    }
    EpisodePhysicsPool pool;
    std::vector<EvalResult> in_turn;
    std::thread one([&] {
      for (const Genome& g : genomes) {
        in_turn.push_back(RunEpisode(problem, g, {}, &pool));
      }
    });
    one.join();
    for (size_t i = 0; i < genomes.size(); ++i) {
      EvalResult reused;
      std::thread t(
          [&] { reused = RunEpisode(problem, genomes[i], {}, &pool); });
      t.join();
      EXPECT_EQ(in_turn[i].fitness, reused.fitness) << path << " " << i;
      pool.Clear();
      const EvalResult fresh = RunEpisode(problem, genomes[i], {}, &pool);
      EXPECT_EQ(in_turn[i].fitness, fresh.fitness) << path << " " << i;
      EXPECT_EQ(in_turn[i].energy, fresh.energy) << path << " " << i;
      EXPECT_EQ(in_turn[i].drift, fresh.drift) << path << " " << i;
      EXPECT_EQ(in_turn[i].fell, fresh.fell) << path << " " << i;
    }
    EXPECT_NE(in_turn[0].fitness, in_turn[1].fitness) << path;
  }
}

// A farm worker runs one episode at a time on whichever of its threads
// takes the job, and builds the run's simulation while it waits for the
// first: no episode of the same body builds it again, in any thread.
TEST(OptimizerEpisode, APreparedSimulationServesEveryThreadsFirstEpisode) {
  const Problem problem = SnakeProblem(0.2);
  EpisodePhysicsPool pool;
  PrepareEpisode(problem, &pool);
  EXPECT_EQ(pool.built(), 1);
  Random random(5);
  for (int i = 0; i < 3; ++i) {
    const Genome g = problem.genome.RandomGenome(random);  // gait genes
    std::thread t(
        [&] { EXPECT_FALSE(RunEpisode(problem, g, {}, &pool).failed); });
    t.join();
  }
  EXPECT_EQ(pool.built(), 1);
}

// The pool is the caller's: two pools share nothing, and a scenario that
// differs in content (not only in how it was written) builds its own.
TEST(OptimizerEpisode, PoolsAreIndependentAndKeyedByScenarioContent) {
  const Problem problem = SnakeProblem(0.2);
  EpisodePhysicsPool first, second;
  PrepareEpisode(problem, &first);
  EXPECT_EQ(first.built(), 1);
  EXPECT_EQ(second.built(), 0);
  RunEpisode(problem, problem.genome.StartGenome(), {}, &second);
  EXPECT_EQ(second.built(), 1);

  Problem renamed = problem;
  renamed.scenario.robots.at(0).name += "_b";
  EXPECT_NE(ScenarioContentHash(renamed.scenario),
            ScenarioContentHash(problem.scenario));
  EXPECT_EQ(ScenarioContentHash(problem.scenario),
            ScenarioContentHash(Problem(problem).scenario));
  EXPECT_EQ(ScenarioContentHash(problem.scenario).size(), 64u);
}

TEST(OptimizerEpisode, ForwardPresetScoresPositiveForwardDistance) {
  const Problem problem = SnakeProblem(6.0);
  const EvalResult r = RunEpisode(problem, problem.genome.StartGenome());
  EXPECT_GT(r.distance, 0.01);
  EXPECT_EQ(r.fitness, r.distance);  // default weights: distance only
  EXPECT_NEAR(r.speed, r.distance / 6.0, 1e-12);
}

TEST(OptimizerBodyGenes, ModuleCountAndScaleRebuildTheChain) {
  Problem problem = SnakeProblem(1.0);
  problem.genome = ReadGenomeString(R"(<genome>
  <gene name="module_count" lower="3" upper="14" start="11"/>
  <gene name="module_scale" lower="0.5" upper="2" start="1"/>
  <gene name="joint_kp" lower="1" upper="20" start="10"/>
  <gene name="module_mass" lower="0.05" upper="0.5" start="0.1"/>
  <gene name="sensor_after" lower="-1" upper="13" start="2"/>
</genome>)",
                                    "body genome");
  // The start genome rebuilds the same chain plus the sensor module.
  ChainOptions same;
  same.sensor_after = {2};
  const Robot expected = MakeChain(same);
  const Scenario s0 = ApplyBodyGenes(problem.scenario, problem.genome,
                                     problem.genome.StartGenome());
  ASSERT_EQ(s0.robots[0].modules.size(), 11u);
  EXPECT_EQ(s0.robots[0].modules[5].position, expected.modules[5].position);
  ASSERT_EQ(s0.robots[0].sensor_modules.size(), 1u);
  EXPECT_EQ(s0.robots[0].sensor_modules[0].left_mod_nr, 2);

  const Scenario s = ApplyBodyGenes(problem.scenario, problem.genome,
                                    Genome{5, 1.5, 4, 0.3, 9});
  const Robot& r = s.robots[0];
  ASSERT_EQ(r.modules.size(), 5u);
  EXPECT_DOUBLE_EQ(r.modules[0].frames[0].scale.x(), 0.075);
  EXPECT_EQ(r.modules[3].joint.kp, 4);
  EXPECT_DOUBLE_EQ(r.modules[3].frames[0].mass + r.modules[3].frames[1].mass,
                   0.3);
  // The sensor module is clamped behind the last module; the chain still
  // stands on the ground.
  ASSERT_EQ(r.sensor_modules.size(), 1u);
  EXPECT_EQ(r.sensor_modules[0].left_mod_nr, 4);
  EXPECT_DOUBLE_EQ(r.modules[0].position.z(), 0.075 / 2);
  EXPECT_FALSE(RunEpisode(problem, Genome{5, 1.5, 4, 0.3, 9}).failed);
}

// A snake whose module_count gene (3..14, starting at 11) can grow it into
// the ball lying where a 14th module would be.
Problem BallBehindTheChainProblem() {
  Problem problem = SnakeProblem(0.5);
  problem.genome = ReadGenomeString(R"(<genome>
  <gene name="module_count" lower="3" upper="14" start="11"/>
</genome>)",
                                    "body genome");
  ChainOptions longer;
  longer.modules = 14;
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.05, 0.05, 0.05);
  ball.position = MakeChain(longer).modules[13].position;
  problem.scenario.scene_objects.push_back(ball);
  return problem;
}

// A body the genes grow into the scene (module_count here, past the ball
// lying behind the chain) overlaps at the start: a failed individual, as
// mrsim-sim refuses such a file, saying which parts overlap; the body
// that stays clear runs.
TEST(OptimizerBodyGenes, ABodyGrownIntoTheBallIsAFailedIndividual) {
  const Problem problem = BallBehindTheChainProblem();
  EXPECT_FALSE(RunEpisode(problem, Genome{11}).failed);
  const EvalResult grown = RunEpisode(problem, Genome{14});
  EXPECT_TRUE(grown.failed);
  EXPECT_EQ(grown.fitness, kFailedFitness);
  EXPECT_EQ(grown.error,
            "overlap at the start: robot 'snake' module 13 back frame / "
            "scene object 'ball'");
}

// mrsim-opt --allow-overlap (the design's allowOverlap): the grown body
// runs, the physics pushing the ball out, as mrsim-sim --allow-overlap
// runs such a file.
TEST(OptimizerBodyGenes, ABodyGrownIntoTheBallRunsWhenOverlapIsAllowed) {
  Problem problem = BallBehindTheChainProblem();
  problem.episode.allow_overlap = true;
  const EvalResult grown = RunEpisode(problem, Genome{14});
  EXPECT_FALSE(grown.failed) << grown.error;
  EXPECT_EQ(grown.error, "");
  EXPECT_GT(grown.energy, 0.0);
}

// The setting travels in the payload a farm's workers decode, so a worker
// runs (or fails) the grown body as one process does; a payload without
// it is what it was before the setting existed.
TEST(OptimizerBodyGenes, AllowingOverlapTravelsInTheProblemPayload) {
  Problem problem = BallBehindTheChainProblem();
  const std::string refused = EncodeProblem(problem);
  EXPECT_EQ(refused.find("allow_overlap"), std::string::npos);
  EXPECT_FALSE(DecodeProblem(refused, "test").episode.allow_overlap);
  problem.episode.allow_overlap = true;
  const Problem allowed = DecodeProblem(EncodeProblem(problem), "test");
  EXPECT_TRUE(allowed.episode.allow_overlap);
  EXPECT_FALSE(RunEpisode(allowed, Genome{14}).failed);
  std::string bad = EncodeProblem(problem);
  const size_t at = bad.find("allow_overlap=1");
  ASSERT_NE(at, std::string::npos);
  bad[at + 14] = '7';
  try {
    DecodeProblem(bad, "payload x");
    ADD_FAILURE() << "allow_overlap=7 was accepted";
  } catch (const ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("allow_overlap: expected 0 or 1"),
              std::string::npos)
        << e.what();
  }
}

// On a farm (master and worker cores on a simulated network, the worker
// decoding the payload and running real episodes) the grown body fails
// with the same reason, or runs when overlap is allowed, and every
// result is the one process's, bit for bit.
TEST(OptimizerBodyGenes, AFarmWorkerDecidesAnOverlappingBodyAsOneProcessDoes) {
  for (const bool allow : {false, true}) {
    Problem problem = BallBehindTheChainProblem();
    problem.episode.allow_overlap = allow;
    const std::string payload = EncodeProblem(problem);
    testing::SimFarm farm(payload, FarmSettings{}, testing::SimNetwork{});
    farm.AddRealWorker("w", 1.0);
    const std::vector<Genome> batch = {Genome{11}, Genome{14}};
    std::vector<EvalResult> results;
    ASSERT_TRUE(farm.Evaluate(batch, 600, &results));
    ASSERT_EQ(results.size(), batch.size());
    const Problem local = DecodeProblem(payload, "local");
    for (size_t i = 0; i < batch.size(); ++i) {
      const EvalResult here = RunEpisode(local, batch[i]);
      EXPECT_EQ(results[i].fitness, here.fitness) << i;
      EXPECT_EQ(results[i].failed, here.failed) << i;
      EXPECT_EQ(results[i].error, here.error) << i;
    }
    EXPECT_EQ(results[1].failed, !allow) << results[1].error;
    EXPECT_EQ(results[1].error.rfind("overlap at the start: ", 0) == 0, !allow)
        << results[1].error;
  }
}

// A body the validator refuses is a failed individual, not an error that
// stops the run (locally) or that every worker reports (on a farm).
TEST(OptimizerEpisode, ABodyTheSimulatorRefusesIsAFailedIndividual) {
  Problem problem = SnakeProblem(0.2);
  GenomeSpec spec;  // built in code: no file limits to stop it
  spec.genes = {{"joint_kp", -5, 1, 0.5, true, false}};
  problem.genome = spec;
  const EvalResult r = RunEpisode(problem, Genome{-4});
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.fitness, kFailedFitness);
  EXPECT_FALSE(RunEpisode(problem, Genome{0.5}).failed);
}

// Ctrl-C during a long episode: the episode is abandoned, not finished.
TEST(OptimizerEpisode, AStopAbandonsALongEpisode) {
  const Problem problem = SnakeProblem(1e6);  // would take days
  int polls = 0;
  EXPECT_THROW(RunEpisode(problem, problem.genome.StartGenome(),
                          [&polls] { return ++polls >= 3; }),
               EvaluationInterrupted);
  EXPECT_EQ(polls, 3);
}

TEST(OptimizerBodyGenes, MovingTheFrontSensorModuleBackDropsItsForwardRay) {
  Problem problem = SnakeProblem(0.5);
  ChainOptions front;
  front.sensor_after = {-1};
  front.front_distance_sensor = true;
  problem.scenario.robots[0] = MakeChain(front);
  problem.genome = ReadGenomeString(R"(<genome>
  <gene name="sensor_after" lower="-1" upper="10" start="-1"/>
</genome>)",
                                    "sensor genome");
  const Scenario kept = ApplyBodyGenes(problem.scenario, problem.genome,
                                       problem.genome.StartGenome());
  EXPECT_EQ(kept.robots[0].sensor_modules[0].distance_sensors.size(), 1u);
  // Behind module 3 the ray would start inside it and read 0.
  const Scenario moved =
      ApplyBodyGenes(problem.scenario, problem.genome, Genome{3});
  ASSERT_EQ(moved.robots[0].sensor_modules.size(), 1u);
  EXPECT_EQ(moved.robots[0].sensor_modules[0].left_mod_nr, 3);
  EXPECT_TRUE(moved.robots[0].sensor_modules[0].distance_sensors.empty());
  EXPECT_FALSE(RunEpisode(problem, Genome{3}).failed);
}

TEST(OptimizerBodyGenes, RebuildAtStartValuesKeepsTheExampleRobots) {
  for (const char* file :
       {"scenarios/snake11.xml", "scenarios/case_study.xml"}) {
    const Scenario original = ReadScenarioFile(testing::SourcePath(file));
    const Robot& r = original.robots[0];
    GenomeSpec spec;
    spec.genes.push_back({"module_count", 1, 20,
                          static_cast<double>(r.modules.size()), true, true});
    const Scenario s = ApplyBodyGenes(original, spec, spec.StartGenome());
    const Robot& b = s.robots[0];
    ASSERT_EQ(b.modules.size(), r.modules.size()) << file;
    for (size_t i = 0; i < r.modules.size(); ++i) {
      EXPECT_TRUE(b.modules[i].position.isApprox(r.modules[i].position, 1e-12))
          << file << " module " << i;
      EXPECT_EQ(b.modules[i].axis, r.modules[i].axis);
      EXPECT_EQ(b.modules[i].joint.kp, r.modules[i].joint.kp);
    }
    ASSERT_EQ(b.sensor_modules.size(), r.sensor_modules.size()) << file;
    for (size_t k = 0; k < r.sensor_modules.size(); ++k) {
      EXPECT_EQ(b.sensor_modules[k].left_mod_nr,
                r.sensor_modules[k].left_mod_nr);
      EXPECT_EQ(b.sensor_modules[k].force_sensor.has_value(),
                r.sensor_modules[k].force_sensor.has_value());
      EXPECT_EQ(b.sensor_modules[k].distance_sensors.size(),
                r.sensor_modules[k].distance_sensors.size());
    }
  }
}

TEST(OptimizerProblem, PayloadRoundTripsAndNamesNoFile) {
  Problem p = SnakeProblem(3.0);
  p.episode.fitness.w_energy = 0.25;
  const std::string payload = EncodeProblem(p);
  const Problem back = DecodeProblem(payload, "test");
  EXPECT_EQ(EncodeProblem(back), payload);
  EXPECT_EQ(back.episode.fitness.w_energy, 0.25);

  p.scenario.scene.height_image = "/etc/hostname_not_an_image";
  std::string bad = EncodeProblem(p);  // not a file here: left as is
  EXPECT_THROW(DecodeProblem(bad, "test"), ProblemError);
  EXPECT_THROW(DecodeProblem("garbage", "test"), ProblemError);
  EXPECT_THROW(DecodeProblem(payload.substr(0, payload.size() / 2), "test"),
               ProblemError);
}

TEST(OptimizerProblem, APayloadNestedTenThousandDeepIsRefusedBeforeParsing) {
  std::string payload = EncodeProblem(SnakeProblem(3.0));
  const size_t at = payload.find("<Scenario");
  ASSERT_NE(at, std::string::npos);
  std::string deep;
  for (int i = 0; i < 10000; ++i) deep += "<a>";
  for (int i = 0; i < 10000; ++i) deep += "</a>";
  payload.insert(at, deep);
  try {
    DecodeProblem(payload, "farm payload");
    FAIL() << "a 10,000-deep payload was accepted";
  } catch (const ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("farm payload"), std::string::npos)
        << e.what();
  }
}

TEST(OptimizerEpisode, SeededLocalRunGivesTheSameResultTwice) {
  const Problem problem = SnakeProblem(1.0);
  AlgorithmSettings settings;
  settings.population = 4;
  settings.seed = 23;
  OptimizationRunOptions options;
  options.generations = 3;
  auto run = [&](int threads) {
    EpisodePhysicsPool pool;
    LocalEvaluator evaluator(
        [&](const Genome& g) { return RunEpisode(problem, g, {}, &pool); },
        threads);
    return RunOptimization(problem.genome, settings, evaluator, options);
  };
  const RunResult a = run(1);
  const RunResult b = run(2);
  EXPECT_EQ(a.best, b.best);
  EXPECT_EQ(a.best_result.fitness, b.best_result.fitness);
  EXPECT_EQ(a.best_generation, b.best_generation);
}

TEST(OptimizerProblem, TerrainImageTravelsInsideThePayload) {
  Problem p = SnakeProblem(1.0);
  p.scenario = ReadScenarioFile(testing::SourcePath("scenarios/terrain.xml"));
  ASSERT_EQ(p.scenario.scene.height_image.rfind("base64:", 0),
            std::string::npos);
  const Problem back = DecodeProblem(EncodeProblem(p), "terrain payload");
  EXPECT_EQ(back.scenario.scene.height_image.rfind("base64:", 0), 0u);
  // Evaluates with no file at hand, the same as the original.
  EXPECT_EQ(RunEpisode(back, back.genome.StartGenome()).fitness,
            RunEpisode(p, p.genome.StartGenome()).fitness);
}

}  // namespace
}  // namespace mrsim

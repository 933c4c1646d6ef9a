// --controller lua:FILE in the optimiser's library: a script's declared
// parameters become the genes, its episodes run the script (a failing
// script gives a failed evaluation with its message), the script travels
// in the problem payload and so in the run's fingerprint, and the best
// individual is a script mrsim-lua runs.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/hash.h"
#include "lua_controller/lua_script.h"
#include "optimizer/episode/best_lua_script.h"
#include "optimizer/episode/controller_genes.h"
#include "optimizer/episode/episode.h"
#include "optimizer/farm/farm_master_core.h"
#include "optimizer/search/local_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "optimizer/episode/problem_codec.h"
#include "optimizer/episode/task.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

ControllerSpec Script(const std::string& source,
                      const std::string& name = "test.lua") {
  ControllerSpec spec;
  spec.kind = ControllerSpec::Kind::kLua;
  spec.source = source;
  spec.name = name;
  return spec;
}

ControllerSpec Serpenoid() {
  return ParseControllerFlag(
      "lua:" + testing::SourcePath("examples/optimise/serpenoid_params.lua"));
}

// The flat task driven by `controller` for `seconds`.
Problem LuaProblem(const ControllerSpec& controller, double seconds) {
  const Task task = MakeTask("flat");
  Problem p = TaskProblem(task, task.gait, GenomeSpec{}, seconds);
  p.controller = controller;
  p.genome = ControllerGenome(controller, nullptr);
  return p;
}

TEST(LuaControllerGenes, DeclaredParametersBecomeGenesWithTheirRanges) {
  GenomeSpec body;
  body.genes = {{"module_mass", 0.1, 0.5, 0.2, true, false}};
  const GenomeSpec spec = ControllerGenome(Serpenoid(), &body);
  ASSERT_EQ(spec.size(), 5);
  const char* names[] = {"amplitude", "phase_lag", "period", "offset",
                         "module_mass"};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(spec.genes[i].name, names[i]);
  EXPECT_EQ(spec.genes[0].lower, 0.0);
  EXPECT_EQ(spec.genes[0].upper, 1.5);
  EXPECT_EQ(spec.genes[0].start, 1.0);
  EXPECT_EQ(spec.genes[2].lower, 1.0);
  EXPECT_EQ(spec.genes[2].upper, 6.0);
  EXPECT_EQ(spec.genes[2].start, 4.0);
  EXPECT_EQ(spec.genes[3].lower, -0.3);
  // The gait's genes are not a script's.
  GenomeSpec gait;
  gait.genes = {{"A_pitch", 0, 1, 0.5, true, false}};
  EXPECT_THROW(ControllerGenome(Serpenoid(), &gait), GenomeError);
}

TEST(LuaControllerGenes, ABadDeclarationIsRefusedNamingTheEntryAndField) {
  const std::string step = "\nfunction step(t, s) return {} end\n";
  struct Case {
    const char* params;
    const char* says;
  };
  const Case cases[] = {
      {"params = {{name='a', min=0, max=1, start=0.5}, {name='b', min=0, "
       "start=1}}",
       "params[2] ('b'): field 'max'"},
      {"params = {{name='a', min=2, max=1, start=1.5}}",
       "params[1] ('a'): field 'min' is above 'max'"},
      {"params = {{name='a', min=0, max=1, start=3}}",
       "field 'start' is outside [min, max]"},
      {"params = {{min=0, max=1, start=0}}", "params[1]: field 'name'"},
      {"params = {{name='a', min=0, max=1, start=0}, {name='a', min=0, "
       "max=1, start=0}}",
       "params[2] ('a'): field 'name' repeats"},
      {"params = {{name='A_pitch', min=0, max=1, start=0}}",
       "parameter 'A_pitch' has the name of a built-in gene"},
      {"params = 3", "params must be an array"},
      {"x = 1", "declares no parameters"},
  };
  for (const Case& c : cases) {
    try {
      ControllerGenome(Script(c.params + step, "bad.lua"), nullptr);
      ADD_FAILURE() << c.params << ": accepted";
    } catch (const GenomeError& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.lua"), std::string::npos)
          << e.what();
    }
  }
}

TEST(LuaControllerGenes, TheGenesReachTheScriptAndEpisodesRepeatBitForBit) {
  const Problem problem = LuaProblem(Serpenoid(), 2.0);
  const Genome start = problem.genome.StartGenome();
  const EvalResult a = RunEpisode(problem, start);
  const EvalResult b = RunEpisode(problem, start);
  EXPECT_FALSE(a.failed) << a.error;
  EXPECT_EQ(a.fitness, b.fitness);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_GT(a.energy, 0.0);
  Genome still = start;
  still[0] = 0.0;  // no amplitude: no wave
  const EvalResult c = RunEpisode(problem, still);
  EXPECT_LT(std::abs(c.distance), std::abs(a.distance));
}

TEST(LuaControllerGenes,
     AScriptThatRaisesGivesAFailedEvaluationWithItsMessage) {
  const Problem problem =
      LuaProblem(Script("params = {{name='a', min=0, max=1, start=0.5}}\n"
                        "function step(t, s)\n"
                        "  if t > 0.2 then error('boom at ' .. P.a) end\n"
                        "  local out = {}\n"
                        "  for i = 1, s.n do out[i] = 0 end\n"
                        "  return out\n"
                        "end\n",
                        "raises.lua"),
                 1.0);
  const EvalResult r = RunEpisode(problem, problem.genome.StartGenome());
  EXPECT_TRUE(r.failed);
  EXPECT_EQ(r.fitness, kFailedFitness);
  EXPECT_NE(r.error.find("raises.lua:3:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("boom at 0.5"), std::string::npos) << r.error;

  // The run goes on, and evaluations.csv carries the message.
  const std::string dir = testing::TempDir("lua_raises_run");
  LocalEvaluator evaluator(
      [&problem](const Genome& g) { return RunEpisode(problem, g); }, 2);
  AlgorithmSettings settings;
  settings.population = 3;
  OptimizationRunOptions options;
  options.generations = 1;
  options.out_dir = dir;
  options.fingerprint = "f";
  options.error_column = true;
  RunOptimization(problem.genome, settings, evaluator, options);
  const std::string csv = ReadAll(dir + "/evaluations.csv");
  EXPECT_NE(csv.find(",error\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("boom at"), std::string::npos) << csv;
  // A resumed run rewrites the same file from its checkpoint.
  options.generations = 1;
  RunOptimization(problem.genome, settings, evaluator, options);
  EXPECT_EQ(ReadAll(dir + "/evaluations.csv"), csv);
}

TEST(LuaControllerGenes, TheScriptTravelsInThePayloadAndItsFingerprint) {
  const Problem problem = LuaProblem(Serpenoid(), 1.0);
  const std::string payload = EncodeProblem(problem);
  const Problem decoded = DecodeProblem(payload, "test");
  EXPECT_EQ(decoded.controller.kind, ControllerSpec::Kind::kLua);
  EXPECT_EQ(decoded.controller.source, problem.controller.source);
  EXPECT_EQ(decoded.controller.name, "serpenoid_params.lua");
  EXPECT_EQ(decoded.genome.size(), problem.genome.size());
  EXPECT_EQ(RunEpisode(decoded, decoded.genome.StartGenome()).fitness,
            RunEpisode(problem, problem.genome.StartGenome()).fitness);
  // One character of the script changes the payload's hash.
  Problem other = problem;
  other.controller.source += " ";
  EXPECT_NE(Fnv1a64(EncodeProblem(other)), Fnv1a64(payload));
  // The gait's payload has no controller section.
  Problem gait = problem;
  gait.controller = ControllerSpec{};
  gait.genome = ForwardGaitGenome();
  EXPECT_EQ(EncodeProblem(gait).find("\ncontroller "), std::string::npos);
}

TEST(LuaControllerGenes, AWorkerHoldingAnotherScriptIsRefused) {
  const Problem problem = LuaProblem(Serpenoid(), 1.0);
  Problem other = problem;
  other.controller.source += "\n-- changed\n";
  FarmMasterCore master(EncodeProblem(problem), "run", 1, FarmSettings{});
  const std::string other_hash = HashHex(Fnv1a64(EncodeProblem(other)));
  ASSERT_NE(other_hash, master.scenario_hash());
  auto beat = [&](const std::string& id, const std::string& hash) {
    opt_heartbeat_t hb{};
    hb.worker_id = id;
    hb.run_id = master.run_id();
    hb.scenario_hash = hash;
    hb.slots = 1;
    hb.build = BuildFingerprint();
    return hb;
  };
  master.OnHeartbeat(beat("same", master.scenario_hash()), 0.0);
  master.OnHeartbeat(beat("other", other_hash), 0.0);
  master.StartBatch({problem.genome.StartGenome(), {0.5, 2.0, 3.0, 0.1}}, 0.0);
  const FarmOutbox out = master.Tick(0.0);
  ASSERT_FALSE(out.jobs.empty());
  for (const opt_job_t& job : out.jobs) EXPECT_EQ(job.worker_id, "same");
  // Its results are not taken either.
  opt_result_t r{};
  r.run_id = master.run_id();
  r.scenario_hash = other_hash;
  r.worker_id = "other";
  r.job_id = out.jobs[0].job_id;
  r.fitness = 1e9;
  master.OnResult(r, 0.1);
  EXPECT_EQ(master.counters().results_ignored, 1);
  EXPECT_EQ(master.counters().results_accepted, 0);
}

TEST(LuaControllerGenes, TheBestScriptRunsWithTheBestValuesExactly) {
  const ControllerSpec controller = Serpenoid();
  GenomeSpec body;
  body.genes = {{"module_mass", 0.1, 0.5, 0.2, true, false}};
  const GenomeSpec spec = ControllerGenome(controller, &body);
  const Genome best = {0.1234567890123456789, 1.0 / 3.0, 2.5, -0.05, 0.3};
  const std::string text = BestLuaScript(controller, spec, best);
  const LuaScript script(text, "best_controller.lua");
  ASSERT_EQ(script.parameters().size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(script.parameters()[i].start, best[i]) << i;
    EXPECT_EQ(script.parameters()[i].name, spec.genes[i].name);
  }
  EXPECT_EQ(text.find("module_mass"), std::string::npos);
}

}  // namespace
}  // namespace mrsim

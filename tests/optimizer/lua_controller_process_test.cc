// mrsim-opt --controller lua:FILE as real processes (LCM ports 7730-7731):
// the example serpenoid on the flat task improves over three generations,
// a farm of two mrsim-worker processes gives the local run's files byte
// for byte, and a script that raises fails its evaluations, not the run.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// The command: CMA-ES, population 4, 3 generations, 3 s episodes.
std::vector<std::string> SerpenoidArgs(const std::string& out,
                                       const std::string& script) {
  return {BinaryPath("optimizer/process/mrsim-opt"),
          "--task",
          "flat",
          "--controller",
          "lua:" + script,
          "--algorithm",
          "cmaes",
          "--population",
          "4",
          "--generations",
          "3",
          "--episode",
          "3",
          "--seed",
          "5",
          "--out",
          out};
}

std::vector<std::string> With(std::vector<std::string> args,
                              const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

const std::string& Serpenoid() {
  static const std::string path =
      SourcePath("examples/optimise/serpenoid_params.lua");
  return path;
}

TEST(LuaControllerProcess, SerpenoidOnFlatImprovesAndWritesARunnableScript) {
  const std::string dir = TempDir("lua_serpenoid_local");
  ChildProcess opt(
      With(SerpenoidArgs(dir, Serpenoid()), {"--workers", "local:2"}),
      dir + "/log.txt");
  ASSERT_EQ(opt.Wait(180), 0) << opt.Output();
  const std::vector<std::string> rows =
      Lines(ReadAll(dir + "/generations.csv"));
  ASSERT_EQ(rows.size(), 4u) << "a header and three generations";
  EXPECT_EQ(rows[0].rfind("generation,best,mean,worst,best_so_far,failed,"
                          "amplitude,phase_lag,period,offset",
                          0),
            0u)
      << rows[0];
  double previous = -1e300;
  for (size_t i = 1; i < rows.size(); ++i) {
    std::istringstream fields(rows[i]);
    std::string field;
    for (int k = 0; k < 5; ++k) std::getline(fields, field, ',');
    const double best_so_far = std::stod(field);
    EXPECT_GE(best_so_far, previous) << rows[i];
    previous = best_so_far;
  }
  EXPECT_GT(previous, 0.0) << "the serpenoid moves the snake forward";
  const std::string best = ReadAll(dir + "/best_controller.lua");
  EXPECT_NE(best.find("function step"), std::string::npos);
  EXPECT_NE(best.find("Written by mrsim-opt"), std::string::npos);
  EXPECT_NE(ReadAll(dir + "/replay.launch").find("mrsim-lua"),
            std::string::npos);
  // mrsim-lua loads it.
  ChildProcess check(
      {BinaryPath("lua_controller/process/mrsim-lua"), "--robot", "snake",
       "--script", dir + "/best_controller.lua", "--check"},
      dir + "/check.txt");
  EXPECT_EQ(check.Wait(30), 0) << check.Output();
}

TEST(LuaControllerProcess, FarmOfTwoWorkersGivesTheLocalRunBitForBit) {
  const std::string local = TempDir("lua_farm_local");
  ChildProcess reference(
      With(SerpenoidArgs(local, Serpenoid()), {"--workers", "local:2"}),
      local + "/log.txt");
  ASSERT_EQ(reference.Wait(180), 0) << reference.Output();
  const std::string url = TestLcmUrl(7730);
  const std::string dir = TempDir("lua_farm");
  std::vector<std::unique_ptr<ChildProcess>> workers;
  for (const char* id : {"w1", "w2"}) {
    workers.push_back(std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("optimizer/process/mrsim-worker"),
                                 "--lcm-url", url, "--id", id},
        dir + "/" + id + ".log"));
  }
  ChildProcess master(
      With(SerpenoidArgs(dir, Serpenoid()), {"--farm", "--lcm-url", url}),
      dir + "/master.log");
  ASSERT_EQ(master.Wait(240), 0) << master.Output();
  for (const char* f : {"/generations.csv", "/evaluations.csv",
                        "/best_controller.lua", "/best_genome.xml"}) {
    const std::string x = ReadAll(local + f);
    EXPECT_FALSE(x.empty()) << f;
    EXPECT_EQ(x, ReadAll(dir + f)) << f;
  }
}

TEST(LuaControllerProcess, AScriptThatRaisesFailsItsEvaluationsOnTheFarm) {
  const std::string dir = TempDir("lua_farm_raises");
  const std::string script = dir + "/raises.lua";
  {
    std::ofstream out(script);
    out << "params = {{name = 'gain', min = 0, max = 1, start = 0.5}}\n"
           "function step(t, state)\n"
           "  error('no controller here')\n"
           "end\n";
  }
  const std::string url = TestLcmUrl(7731);
  ChildProcess worker({BinaryPath("optimizer/process/mrsim-worker"),
                       "--lcm-url", url, "--id", "w1"},
                      dir + "/w1.log");
  std::vector<std::string> args = SerpenoidArgs(dir + "/run", script);
  args[10] = "2";    // generations
  args[12] = "0.5";  // s episodes
  ChildProcess master(With(args, {"--farm", "--lcm-url", url}),
                      dir + "/master.log");
  ASSERT_EQ(master.Wait(120), 0) << master.Output();
  const std::string evals = ReadAll(dir + "/run/evaluations.csv");
  EXPECT_NE(evals.find(",error\n"), std::string::npos) << evals;
  EXPECT_NE(evals.find("raises.lua:3: no controller here"), std::string::npos)
      << evals;
  EXPECT_NE(master.Output().find("failed 4"), std::string::npos)
      << master.Output();
}

}  // namespace
}  // namespace mrsim

// mrsim-opt's command with --controller lua:FILE, in process: the flags
// and what they refuse, a run's files, resume refusing another script, and
// --jump-to, --robust and --islands with a script.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "optimizer/process/opt_command.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

OptCommand Parse(std::vector<std::string> args) {
  CLI::App app;
  OptCommand command;
  AddOptFlags(app, command);
  std::reverse(args.begin(), args.end());  // CLI11 takes them reversed
  app.parse(args);
  return command;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string WriteScript(const std::string& dir, const std::string& name,
                        const std::string& text) {
  fs::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::vector<std::string> LuaArgs(const std::string& script,
                                 const std::string& out) {
  return {"--task",       "flat",   "--controller",  "lua:" + script,
          "--out",        out,      "--episode",     "0.5",
          "--population", "3",      "--generations", "2",
          "--workers",    "local:1"};
}

// Runs the command quietly; returns what it printed.
std::string RunCommand(const OptCommand& c) {
  const OptSetup setup = PrepareOpt(c);
  auto evaluator = MakeOptEvaluator(c, setup, nullptr, nullptr);
  std::FILE* out = std::tmpfile();
  RunOpt(c, setup, *evaluator, out, out);
  std::fflush(out);
  std::rewind(out);
  std::string text;
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, out)) > 0;) {
    text.append(buf, n);
  }
  std::fclose(out);
  return text;
}

const char* kScript =
    "params = {{name = 'gain', min = 0, max = 1, start = 0.5}}\n"
    "function step(t, state)\n"
    "  local out = {}\n"
    "  for i = 1, state.n do out[i] = P.gain * math.sin(2 * t + i) end\n"
    "  return out\n"
    "end\n";

TEST(LuaControllerCommand, TheGaitStillNeedsItsGenesAndTheScriptRefusesThem) {
  const std::string dir = testing::TempDir("lua_command_flags");
  EXPECT_THROW(PrepareOpt(Parse({"--task", "flat", "--out", dir + "/a"})),
               OptInputError);
  const std::string script = WriteScript(dir, "s.lua", kScript);
  try {
    PrepareOpt(Parse({"--task", "flat", "--controller", "lua:" + script,
                      "--genes", "sine", "--out", dir + "/b"}));
    ADD_FAILURE() << "--genes with a script accepted";
  } catch (const OptInputError& e) {
    EXPECT_NE(std::string(e.what()).find("--genes sine"), std::string::npos)
        << e.what();
  }
  try {
    PrepareOpt(
        Parse({"--task", "flat", "--controller", "nn", "--out", dir + "/c"}));
    ADD_FAILURE() << "--controller nn accepted";
  } catch (const OptInputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("--controller 'nn': expected gait, cpg"),
        std::string::npos)
        << e.what();
  }
  // cpg: the gait with the CPG genes.
  const OptSetup cpg = PrepareOpt(
      Parse({"--task", "flat", "--controller", "cpg", "--out", dir + "/d"}));
  EXPECT_TRUE(cpg.problem.controller.is_gait());
  EXPECT_GE(cpg.problem.genome.Find("cpg_coupling"), 0);
}

TEST(LuaControllerCommand, AResumeWithAnotherScriptIsRefusedNamingIt) {
  const std::string dir = testing::TempDir("lua_command_resume");
  const std::string script = WriteScript(dir, "s.lua", kScript);
  const std::string out = dir + "/run";
  RunCommand(Parse(LuaArgs(script, out)));
  EXPECT_TRUE(fs::exists(out + "/best_controller.lua"));
  EXPECT_FALSE(fs::exists(out + "/best_gait.xml"));
  const std::string evals = ReadAll(out + "/evaluations.csv");
  // The same command continues (here: replays) the run.
  RunCommand(Parse(LuaArgs(script, out)));
  EXPECT_EQ(ReadAll(out + "/evaluations.csv"), evals);
  // --jump-to 1 writes the best of generation 1 apart.
  std::vector<std::string> jump = LuaArgs(script, out);
  jump.insert(jump.end(), {"--jump-to", "1"});
  RunCommand(Parse(jump));
  EXPECT_TRUE(fs::exists(out + "/jump-1/best_controller.lua"));
  // Another script (one character) is another run.
  WriteScript(dir, "s.lua", std::string(kScript) + "-- changed\n");
  const OptCommand changed = Parse(LuaArgs(script, out));
  const OptSetup setup = PrepareOpt(changed);
  auto evaluator = MakeOptEvaluator(changed, setup, nullptr, nullptr);
  std::FILE* sink = std::tmpfile();
  try {
    RunOpt(changed, setup, *evaluator, sink, sink);
    ADD_FAILURE() << "a checkpoint of another script was taken";
  } catch (const OptInputError& e) {
    EXPECT_NE(std::string(e.what()).find("script_hash="), std::string::npos)
        << e.what();
  }
  std::fclose(sink);
}

TEST(LuaControllerCommand, RobustIslandsAndBodyGenesWorkWithAScript) {
  const std::string dir = testing::TempDir("lua_command_robust");
  const std::string script = WriteScript(dir, "s.lua", kScript);
  const std::string genome = dir + "/body.genome.xml";
  std::ofstream(genome) << "<genome>\n  <gene name=\"module_mass\" "
                           "lower=\"0.1\" upper=\"0.4\" start=\"0.2\"/>\n"
                           "</genome>\n";
  std::vector<std::string> args = LuaArgs(script, dir + "/run");
  args.insert(args.end(),
              {"--robust", "2", "--islands", "2", "--genome", genome});
  const std::string printed = RunCommand(Parse(args));
  EXPECT_NE(printed.find("island"), std::string::npos) << printed;
  const std::string header = ReadAll(dir + "/run/generations.csv");
  EXPECT_EQ(header.rfind("generation,best,mean,worst,best_so_far,failed,gain,"
                         "module_mass,island",
                         0),
            0u)
      << header;
  // No individual failed: every row's `failed` column is 0.
  std::istringstream rows(header);
  std::string row;
  std::getline(rows, row);
  int count = 0;
  while (std::getline(rows, row)) {
    std::istringstream fields(row);
    std::string field;
    for (int k = 0; k < 6; ++k) std::getline(fields, field, ',');
    EXPECT_EQ(field, "0") << row;
    ++count;
  }
  EXPECT_EQ(count, 2);
}

}  // namespace
}  // namespace mrsim

// The studio's Run and Record: the command lines it would start, and a real
// run of the case study recorded for 2 s of simulated time.
#include "studio/live/live_runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "launcher/program_locator.h"
#include "studio/live/live_link.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

using testing::BinaryPath;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

bool Has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

TEST(LiveRunner, RunSpecsAreCommandLinesAUserCouldType) {
  RunOptions o;
  o.scenario_path = "robots.xml";
  o.robots = {"a", "b"};
  o.clock = ClockMode::kLockstep;
  o.lcm_url = "udpm://239.255.76.67:7000?ttl=0";
  const auto specs = LiveRunner::RunSpecs(o);
  ASSERT_EQ(specs.size(), 3u);
  // Controllers first, so they hear the simulator's first state.
  EXPECT_EQ(specs[0].program, "mrsim-gait");
  EXPECT_EQ(specs[1].name, "gait-b");
  EXPECT_EQ(specs[2].program, "mrsim-sim");
  EXPECT_TRUE(specs[2].required);
  const auto& sim = specs[2].args;
  EXPECT_EQ(sim[0], "robots.xml");
  const auto controllers = std::find(sim.begin(), sim.end(), "--controllers");
  ASSERT_NE(controllers, sim.end());
  EXPECT_EQ(*(controllers + 1), "gait-a");
  EXPECT_EQ(*(controllers + 2), "gait-b");
  EXPECT_TRUE(Has(sim, "lockstep"));  // the clock's word
  EXPECT_FALSE(Has(sim, "--speed"));  // realtime only
  EXPECT_TRUE(Has(specs[0].args, o.lcm_url));

  o.clock = ClockMode::kRealtime;
  o.speed = 0.5;
  o.paused = true;
  const auto rt = LiveRunner::RunSpecs(o)[2].args;
  EXPECT_TRUE(Has(rt, "0.5"));
  EXPECT_TRUE(Has(rt, "--paused"));

  EXPECT_TRUE(Has(LiveRunner::RecordSpec(o, "rec").args, "rec"));
  o.clock = static_cast<ClockMode>(7);  // not a clock the simulator knows
  EXPECT_THROW(LiveRunner::RunSpecs(o), std::invalid_argument);
  o.clock = ClockMode::kFast;
  o.rate = 0;
  EXPECT_THROW(LiveRunner::RunSpecs(o), std::invalid_argument);
  o.rate = 100;
  o.scenario_path.clear();
  EXPECT_THROW(LiveRunner::RunSpecs(o), std::invalid_argument);
}

TEST(LiveRunner, LuaAndExternalControllersStartWhatTheyShould) {
  RunOptions o;
  o.scenario_path = "robots.xml";
  o.robots = {"a"};
  o.controller = ControllerKind::kLua;
  o.lua_script = "ctl.lua";
  o.clock = ClockMode::kLockstep;
  auto specs = LiveRunner::RunSpecs(o);
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[0].program, "mrsim-lua");
  EXPECT_TRUE(Has(specs[0].args, "ctl.lua"));
  EXPECT_TRUE(Has(specs[1].args, "lua-a"));  // --controllers lua-a
  o.lua_script.clear();
  EXPECT_THROW(LiveRunner::RunSpecs(o), std::invalid_argument);

  // External: nothing but the simulator, in lockstep whatever the form
  // says, waiting for the named program.
  o.controller = ControllerKind::kExternal;
  o.external_name = "my-python";
  o.clock = ClockMode::kRealtime;
  specs = LiveRunner::RunSpecs(o);
  ASSERT_EQ(specs.size(), 1u);
  EXPECT_EQ(specs[0].program, "mrsim-sim");
  EXPECT_TRUE(Has(specs[0].args, "lockstep"));
  EXPECT_TRUE(Has(specs[0].args, "my-python"));
  EXPECT_FALSE(Has(specs[0].args, "--speed"));
  for (const std::string bad : {"", "two words", "a;rm", "-x", "--paused"}) {
    o.external_name = bad;
    EXPECT_THROW(LiveRunner::RunSpecs(o), std::invalid_argument) << bad;
  }
  o.controller = static_cast<ControllerKind>(7);  // not a kind
  EXPECT_THROW(LiveRunner::RunSpecs(o), std::invalid_argument);
}

bool PollUntil(LiveLink& link, LiveRunner& runner,
               const std::function<bool()>& done, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    link.Poll(20);
    runner.Poll();
  }
  return true;
}

std::string Console(const LiveRunner& runner) {
  std::string all;
  for (const auto& line : runner.console()) all += line + "\n";
  return all;
}

struct StateRow {
  int64_t seq = 0;
  double sim_time = 0;
};

// The seq and sim_time columns of a state CSV mrsim-log wrote.
std::vector<StateRow> ReadStateRows(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::stringstream ss(text);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    return cells;
  };
  const std::vector<std::string> header = split(line);
  const auto column = [&](const std::string& name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) -
                               header.begin());
  };
  const size_t seq = column("seq");
  const size_t sim_time = column("sim_time");
  std::vector<StateRow> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line);
    if (seq >= cells.size() || sim_time >= cells.size()) {
      ADD_FAILURE() << path << ": a row without seq or sim_time: " << line;
      break;
    }
    rows.push_back({std::stoll(cells[seq]), std::stod(cells[sim_time])});
  }
  return rows;
}

TEST(LiveRunner, RunsTheCaseStudyAndRecordsEveryStateOfTwoSeconds) {
  const std::string url = TestLcmUrl(7966);
  const std::string dir = TempDir("live_runner");
  LiveRunner runner({std::filesystem::path(BinaryPath("bin/mrsim-sim"))
                         .parent_path()
                         .string()});
  RunOptions o;
  o.scenario_path = SourcePath("scenarios/case_study.xml");
  o.robots = {"case_study"};
  o.lcm_url = url;
  o.paused = true;
  runner.Start(o);

  LiveSessionOptions so;
  so.sender = "studio-runner-test";
  so.request_timeout_s = 20;
  LiveSession session(so);
  LiveLink link(url, &session);
  ASSERT_TRUE(PollUntil(
      link, runner,
      [&] {
        const LiveRobot* r = session.robot("case_study");
        return r != nullptr && r->states > 0 && r->gait.has_value();
      },
      60))
      << Console(runner);
  EXPECT_TRUE(runner.running());

  runner.StartRecording(dir + "/rec");
  ASSERT_TRUE(PollUntil(
      link, runner,
      [&] {
        return Console(runner).find("[log] mrsim-log: recording") !=
               std::string::npos;
      },
      60))
      << Console(runner);
  const double t0 = session.robot("case_study")->state.sim_time;
  StudioOutbox out;
  const int64_t step = session.Step(200, WallClock::now(), &out);
  link.Publish(&out);
  ASSERT_TRUE(PollUntil(
      link, runner,
      [&] {
        return session.robot("case_study")->state.sim_time >= t0 + 2 - 1e-9;
      },
      120))
      << Console(runner);
  EXPECT_EQ(session.request(step)->state, LiveRequest::State::kDone);
  runner.StopRecording();
  EXPECT_FALSE(runner.recording());

  const auto files = runner.RecordedFiles();
  const auto state = std::find_if(files.begin(), files.end(), [](auto& f) {
    return f.path.find("MRSIM_STATE_case_study.csv") != std::string::npos;
  });
  ASSERT_NE(state, files.end()) << Console(runner);
  // One row per period stepped, each once. While paused the simulator
  // sends its newest state again every 0.5 s (a late listener's picture):
  // between the logger's start and the step, as many such re-sends as
  // half-seconds went by on a busy machine may be recorded, all of them
  // the one state before the first step.
  const std::vector<StateRow> rows = ReadStateRows(state->path);
  ASSERT_EQ(static_cast<int64_t>(rows.size()), state->rows);
  std::vector<StateRow> stepped, before;
  for (const StateRow& row : rows) {
    (row.sim_time > t0 + 1e-9 ? stepped : before).push_back(row);
  }
  for (const StateRow& row : before) {
    EXPECT_NEAR(row.sim_time, t0, 1e-9) << "a state from before the step";
    EXPECT_EQ(row.seq, before.front().seq) << "not the paused state again";
  }
  ASSERT_EQ(stepped.size(), 200u);
  for (size_t i = 1; i < stepped.size(); ++i) {
    EXPECT_EQ(stepped[i].seq, stepped[i - 1].seq + 1) << i;
  }

  runner.Stop();
  EXPECT_FALSE(runner.running());
  EXPECT_NE(Console(runner).find("[launch] sim"), std::string::npos);
}

// Each Record gets a folder of its own: a second recording never
// overwrites the first.
TEST(LiveRunner, EveryRecordingGetsAFolderOfItsOwn) {
  const std::string base = TempDir("recording_folders");
  std::tm t{};
  t.tm_year = 2026 - 1900;
  t.tm_mon = 10;
  t.tm_mday = 26;
  t.tm_hour = 14;
  t.tm_min = 5;
  t.tm_sec = 9;
  t.tm_isdst = -1;
  const std::time_t when = std::mktime(&t);
  const std::string first = NewRecordingFolder(base, when);
  EXPECT_EQ(first, base + "/2026-11-26_14-05-09");
  EXPECT_FALSE(std::filesystem::exists(first));  // nothing created
  std::filesystem::create_directories(first);
  EXPECT_EQ(NewRecordingFolder(base, when), first + "_2");
  std::filesystem::create_directories(first + "_2");
  EXPECT_EQ(NewRecordingFolder(base, when), first + "_3");
}

}  // namespace
}  // namespace mrsim::studio

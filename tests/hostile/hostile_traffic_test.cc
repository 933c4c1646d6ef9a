// Mutated copies of every channel's own traffic (bit flips, truncations,
// length fields at -1, 0, 2^31-1 and INT32_MIN, a valid fingerprint followed
// by random bytes), tens of thousands of datagrams, sent to the group while
// the simulator, a gait controller, the logger, a viewer and a farm (master
// and worker) run: all stay alive, the simulator still answers mrsim-ctl
// status and its states keep flowing, and the logger's part files stay
// within their cap. The studio, attached to a run, gets the same.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <csignal>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "common/hash.h"
#include "lcmtypes/runtime/decode.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#ifdef MRSIM_HOSTILE_STUDIO
#include "tests/studio/studio_test_util.h"
#endif

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;
using testing::WaitUntil;
#ifdef MRSIM_HOSTILE_STUDIO
using testing::ClickAt;
using testing::ReadLayout;
using testing::WaitForLayout;
using testing::WidgetCentre;
using testing::Xdotool;
using testing::XvfbDisplay;
#endif

// Real datagrams by channel, a few of each.
class Recorder {
 public:
  void On(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    auto& list = by_channel_[channel];
    if (list.size() < 8) {
      const auto* p = static_cast<const uint8_t*>(rbuf->data);
      list.emplace_back(p, p + rbuf->data_size);
    }
    if (channel == "MRSIM_STATE_snake") {
      robot_state_t s;
      if (DecodeMessage(rbuf, &s)) ++states_;
    }
  }
  const std::map<std::string, std::vector<std::vector<uint8_t>>>& samples()
      const {
    return by_channel_;
  }
  int64_t states() const { return states_; }

 private:
  std::map<std::string, std::vector<std::vector<uint8_t>>> by_channel_;
  int64_t states_ = 0;
};

template <class Message>
std::vector<uint8_t> Encode(const Message& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// One mutated copy of `real`, of the kind `kind` picks.
std::vector<uint8_t> Mutate(const std::vector<uint8_t>& real, int kind,
                            bool may_decode, std::mt19937& random) {
  std::vector<uint8_t> m = real;
  auto at = [&](size_t n) {
    return std::uniform_int_distribution<size_t>(0, n - 1)(random);
  };
  // A control request that still decodes could be a QUIT or a PAUSE, which
  // any host may send unless messages are signed: those only get the
  // mutations that cannot decode.
  if (!may_decode && kind < 2) kind = 2 + kind;
  switch (kind) {
    case 0: {  // bit flips after the fingerprint
      const int flips = 1 + static_cast<int>(at(8));
      for (int k = 0; k < flips && m.size() > 8; ++k) {
        m[8 + at(m.size() - 8)] ^= static_cast<uint8_t>(1u << at(8));
      }
      break;
    }
    case 1: {  // a 4-byte field (a length, mostly) set to an absurd value
      static const uint32_t kValues[] = {0xffffffffu, 0x7fffffffu, 0x80000000u,
                                         0u, 0x00010000u};
      if (m.size() >= 12) {
        const size_t offset = 8 + at(m.size() - 11);
        const uint32_t v = kValues[at(5)];
        for (int b = 0; b < 4; ++b) {
          m[offset + b] = static_cast<uint8_t>(v >> (24 - 8 * b));
        }
      }
      break;
    }
    case 2:  // truncated
      m.resize(at(m.size()));
      break;
    default: {  // the fingerprint, then random bytes
      m.resize(8 + at(2 * real.size() + 16));
      for (size_t k = 8; k < m.size(); ++k)
        m[k] = static_cast<uint8_t>(at(256));
      break;
    }
  }
  return m;
}

// Sends `count` mutated copies of `samples` (round robin over channels),
// letting receivers breathe now and then as a real sender would; the flood
// still comes far faster than any real traffic. Control requests only get
// the mutations that cannot decode: one that still decoded could be a QUIT
// or a PAUSE, which any host may send unless messages are signed.
void Flood(
    lcm::LCM* lcm,
    const std::map<std::string, std::vector<std::vector<uint8_t>>>& samples,
    int count, unsigned seed) {
  std::mt19937 random(seed);
  int sent = 0;
  while (sent < count) {
    for (const auto& [channel, list] : samples) {
      const bool may_decode = channel != "MRSIM_SIM_CONTROL";
      const auto& real = list[static_cast<size_t>(sent) % list.size()];
      const std::vector<uint8_t> m = Mutate(real, sent % 4, may_decode, random);
      lcm->publish(channel, m.data(), static_cast<unsigned>(m.size()));
      ++sent;
    }
    if (sent % 200 < static_cast<int>(samples.size())) lcm->handleTimeout(1);
  }
}

TEST(HostileTraffic, EveryProcessSurvivesMutatedCopiesOfItsOwnTraffic) {
  const std::string url = TestLcmUrl(7990);
  const std::string dir = TempDir("hostile_traffic");
  const std::string scenario = SourcePath("scenarios/snake11.xml");
  std::vector<std::unique_ptr<ChildProcess>> all;
  auto start = [&](std::vector<std::string> argv, const std::string& name) {
    all.push_back(
        std::make_unique<ChildProcess>(argv, dir + "/" + name + ".log"));
    return all.back().get();
  };
  ChildProcess* sim =
      start({BinaryPath("sim_core/sim_process/mrsim-sim"), scenario,
             "--lcm-url", url, "--clock", "realtime", "--rate", "50"},
            "sim");
  ChildProcess* gait =
      start({BinaryPath("gait_controller/process/mrsim-gait"), "--robot",
             "snake", "--scenario", scenario, "--lcm-url", url, "--name", "g"},
            "gait");
  ChildProcess* logger = start({BinaryPath("logger/process/mrsim-log"),
                                "--lcm-url", url, "--out", dir + "/log"},
                               "logger");
  ChildProcess* viewer =
      start({BinaryPath("viewer/process/mrsim-view"), scenario, "--lcm-url",
             url, "--out", dir + "/view.mp4", "--fps", "5", "--width", "160",
             "--height", "120"},
            "viewer");
  ChildProcess* worker = start({BinaryPath("optimizer/process/mrsim-worker"),
                                "--lcm-url", url, "--id", "w1"},
                               "worker");
  // A run far longer than the test: it must still be running when the
  // flood is over. 1000 generations (most individuals found in the
  // evaluation cache) ended in 29 s during a fresh-clone CI run, before
  // the checks.
  ChildProcess* master =
      start({BinaryPath("optimizer/process/mrsim-opt"), scenario, "--genome",
             SourcePath("scenarios/forward_gait.genome.xml"), "--generations",
             "1000000", "--population", "4", "--episode", "0.5", "--seed", "3",
             "--out", dir + "/opt", "--farm", "--lcm-url", url},
            "master");

  ASSERT_TRUE(viewer->WaitForOutput("listening", 60)) << viewer->Output();
  ASSERT_TRUE(logger->WaitForOutput("recording", 60)) << logger->Output();
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Recorder rec;
  lcm.subscribe(".*", &Recorder::On, &rec);
  // Worker w1's jobs go on its shard of the job channels (farm_channels.h).
  char job_channel[32];
  std::snprintf(job_channel, sizeof job_channel, "MRSIM_OPT_JOB_%02x",
                static_cast<unsigned>(Fnv1a64(std::string("w1")) % 256));
  const std::vector<std::string> wanted = {
      "MRSIM_STATE_snake",   "MRSIM_SIM_STATUS",
      "MRSIM_COMMAND_snake", "MRSIM_GAIT_STATUS_snake",
      "MRSIM_OPT_RUN",       "MRSIM_OPT_HEARTBEAT",
      job_channel,           "MRSIM_OPT_RESULT"};
  auto have_all = [&] {
    for (const std::string& c : wanted) {
      if (rec.samples().count(c) == 0) return false;
    }
    return true;
  };
  ASSERT_TRUE(WaitUntil(
      [&] {
        lcm.handleTimeout(20);
        return have_all();
      },
      120))
      << "channels heard: " << rec.samples().size() << "\n"
      << master->Output();

  // Our own traffic on the channels nobody sent on yet: a control request
  // and a gait command, as mrsim-ctl would send them.
  std::map<std::string, std::vector<std::vector<uint8_t>>> samples =
      rec.samples();
  {
    sim_control_t control{};
    control.seq = 1;
    control.sender = "mrsim-ctl";
    control.command = sim_control_t::STEP;
    control.steps = 1;
    gait_command_t command{};
    command.seq = 1;
    command.sender = "mrsim-ctl";
    command.robot = "snake";
    command.motion = "forward";
    command.strength = 1;
    samples["MRSIM_SIM_CONTROL"].push_back(Encode(control));
    samples["MRSIM_GAIT_snake"].push_back(Encode(command));
  }

  Flood(&lcm, samples, 30000, 29);

  // Everybody alive and serving: the simulator answers and states flow.
  // They are counted on a fresh socket: the old one still holds our own
  // mutated states, and a bit-flipped seq there would look like progress
  // (or hide it).
  for (const auto& p : all) EXPECT_TRUE(p->running()) << p->Output();
  lcm::LCM after_flood(url);
  ASSERT_TRUE(after_flood.good());
  Recorder fresh;
  after_flood.subscribe("MRSIM_STATE_snake", &Recorder::On, &fresh);
  EXPECT_TRUE(WaitUntil(
      [&] {
        after_flood.handleTimeout(20);
        return fresh.states() > 10;
      },
      120))
      << "states stopped after the flood\n"
      << sim->Output();
  ChildProcess ctl({BinaryPath("tools/mrsim-ctl"), "--lcm-url", url,
                    "--timeout", "45", "status"},
                   dir + "/ctl.log");
  EXPECT_EQ(ctl.Wait(120), 0) << ctl.Output();
  for (const auto& p : all) EXPECT_TRUE(p->running()) << p->Output();

  // Clean stops; the logger's part files stay within their cap.
  for (ChildProcess* p : {master, worker, viewer, gait, sim, logger}) {
    p->Signal(SIGINT);
  }
  // Deadlines for a suite at -j6 on 2 cores, where six processes flushing
  // at once (the viewer finishing its video) can take tens of seconds.
  EXPECT_EQ(sim->Wait(90), 0) << sim->Output();
  EXPECT_EQ(logger->Wait(90), 0) << logger->Output();
  EXPECT_EQ(gait->Wait(90), 0) << gait->Output();
  viewer->Wait(90);
  // The viewer heard the states and refused the forged ones (its summary:
  // "done: ... N states, M malformed, ...").
  const std::string view = viewer->Output();
  const size_t done = view.find("done:");
  ASSERT_NE(done, std::string::npos) << view;
  const std::string summary = view.substr(done, view.find('\n', done) - done);
  EXPECT_EQ(summary.find(" 0 states"), std::string::npos) << summary;
  EXPECT_EQ(summary.find(" 0 malformed"), std::string::npos) << summary;
  master->Wait(90);
  worker->Wait(90);
  std::map<std::string, int> parts;
  for (const auto& e : std::filesystem::directory_iterator(dir + "/log")) {
    const std::string name = e.path().filename().string();
    ++parts[name.substr(0, name.find('.'))];
  }
  for (const auto& [channel, files] : parts) {
    EXPECT_LE(files, 8) << channel;
  }
}

#ifdef MRSIM_HOSTILE_STUDIO
// The studio, attached to a running simulation as its Attach button does,
// hears mutated copies of every channel it listens to: it stays up, keeps
// following the robot, and quits cleanly afterwards.
TEST(HostileTraffic, AttachedStudioSurvivesMutatedCopiesOfTheRunsTraffic) {
  namespace fs = std::filesystem;
  if (!fs::exists("/usr/bin/Xvfb") || !fs::exists("/usr/bin/xdotool")) {
    GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  }
  const std::string url = TestLcmUrl(7992);
  const std::string dir = TempDir("hostile_traffic_studio");
  const std::string scenario = SourcePath("scenarios/snake11.xml");
  ChildProcess sim({BinaryPath("sim_core/sim_process/mrsim-sim"), scenario,
                    "--lcm-url", url, "--clock", "realtime", "--rate", "50"},
                   dir + "/sim.log");
  ChildProcess gait(
      {BinaryPath("gait_controller/process/mrsim-gait"), "--robot", "snake",
       "--scenario", scenario, "--lcm-url", url, "--name", "g"},
      dir + "/gait.log");
  XvfbDisplay xvfb(dir);
  ASSERT_TRUE(xvfb.ok());
  setenv("XDG_CONFIG_HOME", dir.c_str(), 1);
  // The Run panel's URL field starts as LCM_DEFAULT_URL: this test's port.
  setenv("LCM_DEFAULT_URL", url.c_str(), 1);
  const std::string layout = dir + "/layout.txt";
  ChildProcess studio(
      {BinaryPath("studio/mrsim-studio"), "--layout-dump", layout, scenario},
      dir + "/studio.log");
  ASSERT_TRUE(WaitForLayout(layout, "revision", "0")) << studio.Output();
  ASSERT_TRUE(Xdotool({"key", "F5"}));  // the Run panel
  int x = 0, y = 0;
  ASSERT_TRUE(
      WaitUntil([&] { return WidgetCentre(layout, "Attach", &x, &y); }, 60));
  ASSERT_TRUE(ClickAt(x, y));
  auto live_time = [&] {
    std::istringstream in(ReadLayout(layout)["live snake"]);
    double t = -1;
    in >> t;
    return t;
  };
  ASSERT_TRUE(WaitUntil([&] { return live_time() > 0; }, 120))
      << studio.Output();

  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Recorder rec;
  lcm.subscribe(".*", &Recorder::On, &rec);
  const std::vector<std::string> wanted = {
      "MRSIM_STATE_snake", "MRSIM_SIM_STATUS", "MRSIM_COMMAND_snake",
      "MRSIM_GAIT_STATUS_snake"};
  ASSERT_TRUE(WaitUntil(
      [&] {
        lcm.handleTimeout(20);
        for (const std::string& c : wanted) {
          if (rec.samples().count(c) == 0) return false;
        }
        return true;
      },
      120));
  Flood(&lcm, rec.samples(), 20000, 31);

  EXPECT_TRUE(studio.running()) << studio.Output();
  // It heard the flood: what did not decode was counted and dropped.
  EXPECT_TRUE(WaitUntil(
      [&] {
        std::istringstream in(ReadLayout(layout)["live dropped"]);
        int64_t malformed = 0;
        in >> malformed;
        return malformed > 0;
      },
      60))
      << ReadLayout(layout)["live dropped"];
  // A forged state that still decoded may be the one shown for a moment
  // (any time at all, unsigned): the robot is followed when the time shown
  // moves on by a plausible half second or more.
  double reference = live_time();
  EXPECT_TRUE(WaitUntil(
      [&] {
        const double t = live_time();
        if (t > reference + 0.5 && t < reference + 30) return true;
        if (!(t > reference && t < reference + 30)) reference = t;
        return false;
      },
      60))
      << "the studio stopped following the robot\n"
      << studio.Output();
  ASSERT_TRUE(Xdotool({"key", "ctrl+q"}));
  EXPECT_EQ(studio.Wait(90), 0) << studio.Output();
  sim.Signal(SIGINT);
  gait.Signal(SIGINT);
  EXPECT_EQ(sim.Wait(30), 0) << sim.Output();
  EXPECT_EQ(gait.Wait(30), 0) << gait.Output();
}
#endif  // MRSIM_HOSTILE_STUDIO

}  // namespace
}  // namespace mrsim

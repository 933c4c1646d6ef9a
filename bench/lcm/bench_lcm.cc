// bench_lcm: what LCM costs the simulator, measured in one run.
//  (a) closed-loop lockstep over LCM (mrsim-sim + a controller process,
//      100 Hz control, 2 ms physics step), strict and pipelined
//      (--actuation-delay 1, and 2; strict and delay 1 also --no-spin),
//      vs the same loop in one process;
//  (b) mrsim-sim's server publishing state at 100 Hz vs not publishing
//      (fast clock);
//  (c) round trip of a state-sized robot_state_t through encode/decode and a
//      typed handler vs a bare ping-pong of an 8-byte raw message;
//  (d) signed messages (--key-file): pipelined lockstep and (b)'s publishing
//      with a key over the same without.
// LCM ports 7900-7909. Prints BENCH lines (bench/run).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/subprocess.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/message_auth.h"
#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "sim_core/chain_builder.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics.h"
#include "sim_core/scenario_xml.h"
#include "sim_core/sim_process/sim_server.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRate = 100.0;
constexpr int kRepeats = 3;

std::string Url(int port) {
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
}

double Seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// A child process, terminated and reaped on destruction; its CPU time is
// read once it ended.
class Child {
 public:
  explicit Child(const std::vector<std::string>& args,
                 const std::string& out = "/dev/null")
      : process_(args, mrsim::SpawnOptions::ToFile(out)) {}
  // Waits for it to end by itself (up to timeout_s).
  void WaitExit(double timeout_s) { process_.Wait(timeout_s); }
  void Stop() { process_.Stop(); }
  // CPU seconds (user + system) the child used; valid once it ended.
  double cpu_seconds() const { return process_.cpu_seconds(); }

 private:
  mrsim::Subprocess process_;
};

// The controller law of both loops: a travelling wave with a little
// feedback, a pure function of the state message.
std::vector<double> WaveTargets(const mrsim::robot_state_t& s) {
  std::vector<double> t(s.num_joints);
  for (int i = 0; i < s.num_joints; ++i) {
    t[i] = 0.8 * std::sin(2.0 * M_PI * s.sim_time / 1.5 + 0.7 * i) +
           0.05 * s.joints[i].angle;
  }
  return t;
}

// --controller URL: answers every state with a command (lockstep peer).
class Controller {
 public:
  explicit Controller(mrsim::SignedLcm& lcm) : lcm_(lcm) {}
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    mrsim::robot_state_t s;
    if (!mrsim::DecodeMessage(rbuf, &s)) return;
    mrsim::joint_command_t cmd;
    cmd.utime = s.utime;
    cmd.seq = ++seq_;
    cmd.robot = s.robot;
    cmd.sender = "bench";
    cmd.state_seq = s.seq;
    cmd.target = WaveTargets(s);
    cmd.num_joints = static_cast<int32_t>(cmd.target.size());
    lcm_.publish(mrsim::CommandChannel(mrsim::kDefaultChannelPrefix, s.robot),
                 &cmd);
  }

 private:
  mrsim::SignedLcm& lcm_;
  int64_t seq_ = 0;
};

// Signs with $MRSIM_KEY_FILE when the bench sets it, as mrsim-sim does.
int RunController(const std::string& url) {
  mrsim::InstallStopHandlers();
  mrsim::SignedLcm lcm(url, mrsim::LoadAuthConfig("", false));
  if (!lcm.good()) return 1;
  Controller c(lcm);
  lcm.subscribe(std::string(mrsim::kDefaultChannelPrefix) + "_STATE_.*",
                &Controller::OnState, &c)
      ->setQueueCapacity(1000);
  while (!mrsim::StopRequested()) mrsim::HandleFor(lcm, 100);
  return 0;
}

// --echo URL: sends back what it gets: typed state messages decoded and
// re-encoded, raw pings as bytes.
class Echo {
 public:
  explicit Echo(lcm::LCM& lcm) : lcm_(lcm) {}
  void OnState(const lcm::ReceiveBuffer*, const std::string&,
               const mrsim::robot_state_t* msg) {
    lcm_.publish("BENCH_STATE_PONG", msg);
  }
  void OnRaw(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    lcm_.publish("BENCH_RAW_PONG", rbuf->data, rbuf->data_size);
  }

 private:
  lcm::LCM& lcm_;
};

int RunEcho(const std::string& url) {
  mrsim::InstallStopHandlers();
  lcm::LCM lcm(url);
  if (!lcm.good()) return 1;
  Echo e(lcm);
  lcm.subscribe("BENCH_STATE_PING", &Echo::OnState, &e);
  lcm.subscribe("BENCH_RAW_PING", &Echo::OnRaw, &e);
  while (!mrsim::StopRequested()) mrsim::HandleFor(lcm, 100);
  return 0;
}

double InProcessLoop(const std::string& scenario, double duration);

// --inprocess SCENARIO DURATION: the baseline loop, run as its own process
// like mrsim-sim so both get the same share of a busy machine.
int RunInProcess(const std::string& scenario, const std::string& duration) {
  std::cout << "real-time factor "
            << InProcessLoop(scenario, std::stod(duration)) << std::endl;
  return 0;
}

std::string SelfPath() {
  return std::filesystem::read_symlink("/proc/self/exe").string();
}

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Sim seconds per wall second of the closed loop in one process.
double InProcessLoop(const std::string& scenario, double duration) {
  mrsim::Physics physics(mrsim::ReadScenarioFile(scenario));
  const int steps =
      static_cast<int>(std::lround(1.0 / (kRate * physics.timestep())));
  const int periods = static_cast<int>(std::lround(duration * kRate));
  const auto start = Clock::now();
  for (int k = 0; k < periods; ++k) {
    const mrsim::robot_state_t msg =
        mrsim::ToRobotStateMessage(physics.ReadRobotState(0), k);
    physics.SetJointTargets(0, WaveTargets(msg));
    physics.Step(steps);
  }
  return physics.time() / Seconds(Clock::now() - start);
}

// Sim seconds per wall second of mrsim-sim + controller in lockstep, as
// mrsim-sim reports it (from its first period to its last). The bench
// itself stays off the LCM network meanwhile: on udpm every member of the
// group wakes for every message, and a third process would slow the loop.
double ReadFactor(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string key = "real-time factor ";
  const size_t at = text.str().rfind(key);
  if (at == std::string::npos) {
    throw std::runtime_error(path + ": no real-time factor in: " + text.str());
  }
  return std::stod(text.str().substr(at + key.size()));
}

// Pace of a loop: sim s per wall s (as the process reports it) and sim s
// per CPU s of all its processes.
struct Pace {
  double wall = 0;
  double cpu = 0;
};

Pace LocalLoop(const std::string& scenario, double duration,
               const std::string& dir) {
  const std::string out = dir + "/local.out";
  double cpu = 0;
  {
    Child local({SelfPath(), "--inprocess", scenario, std::to_string(duration)},
                out);
    local.WaitExit(120);
    cpu = local.cpu_seconds();
  }
  return {ReadFactor(out), duration / cpu};
}

Pace LcmLoop(const std::string& scenario, double duration, int port,
             const std::string& dir, int delay, bool spin = true) {
  std::ostringstream d;
  d << duration;
  const std::string out = dir + "/sim.out";
  double cpu = 0;
  {
    std::vector<std::string> args = {MRSIM_SIM_BINARY,
                                     scenario,
                                     "--lcm-url",
                                     Url(port),
                                     "--clock",
                                     "lockstep",
                                     "--controllers",
                                     "bench",
                                     "--rate",
                                     "100",
                                     "--duration",
                                     d.str(),
                                     "--lockstep-timeout",
                                     "30",
                                     "--actuation-delay",
                                     std::to_string(delay)};
    if (!spin) args.push_back("--no-spin");
    Child sim(args, out);
    Child controller({SelfPath(), "--controller", Url(port)});
    sim.WaitExit(120);
    controller.Stop();
    cpu = sim.cpu_seconds() + controller.cpu_seconds();
  }
  return {ReadFactor(out), duration / cpu};
}

// SimServer on the fast clock, in this process.
Pace ServerRun(const std::string& scenario, double duration, bool publish,
               int port, const mrsim::AuthConfig& auth = {}) {
  mrsim::SignedLcm lcm(Url(port), auth);
  mrsim::SimOptions options;
  options.clock = mrsim::ClockMode::kFast;
  options.rate = kRate;
  options.duration = duration;
  options.publish_state = publish;
  std::ostringstream log;
  mrsim::SimServer server(
      lcm, std::make_unique<mrsim::Physics>(mrsim::ReadScenarioFile(scenario)),
      options, log);
  const auto start = Clock::now();
  const double cpu_start = CpuSeconds();
  server.Run([] { return false; });
  const double t = server.physics().time();
  return {t / Seconds(Clock::now() - start), t / (CpuSeconds() - cpu_start)};
}

struct Pong {
  bool got = false;
  void OnState(const lcm::ReceiveBuffer*, const std::string&,
               const mrsim::robot_state_t*) {
    got = true;
  }
  void OnRaw(const lcm::ReceiveBuffer*, const std::string&) { got = true; }
};

// Mean round trip (us) of n pings of either kind.
double RoundTrip(lcm::LCM& lcm, Pong& pong, bool state,
                 const mrsim::robot_state_t& msg, int n) {
  const uint64_t raw = 0x6d7273696dULL;
  double total = 0;
  int done = 0;
  for (int i = 0; i < n + 50; ++i) {
    pong.got = false;
    const auto start = Clock::now();
    if (state) {
      lcm.publish("BENCH_STATE_PING", &msg);
    } else {
      lcm.publish("BENCH_RAW_PING", &raw, sizeof(raw));
    }
    const auto deadline = start + std::chrono::seconds(1);
    while (!pong.got && Clock::now() < deadline) mrsim::HandleFor(lcm, 10);
    if (!pong.got) continue;  // lost: not a round trip
    if (i >= 50) {            // warm-up excluded
      total += Seconds(Clock::now() - start);
      ++done;
    }
  }
  if (done == 0) throw std::runtime_error("no round trip completed");
  return total / done * 1e6;
}

double Best(const std::vector<double>& v) {
  return *std::max_element(v.begin(), v.end());
}

// --signed: only (d), the two signed figures (a few minutes instead of
// about ten), each pair measured back to back.
int RunSignedBench() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("mrsim_bench_lcm_signed_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  mrsim::Scenario scenario;
  mrsim::ChainOptions chain;
  chain.modules = 11;
  scenario.robots.push_back(mrsim::MakeChain(chain));
  scenario.settings.timestep = 0.002;
  const std::string path = (dir / "snake11.xml").string();
  mrsim::WriteScenarioFile(scenario, path);
  const std::string key = (dir / "bench.key").string();
  mrsim::WriteKeyFile(key);
  const mrsim::AuthConfig auth = mrsim::LoadAuthConfig(key, false);
  const double duration = 20.0;
  std::vector<double> piped, piped_signed, loud, loud_signed;
  // Which of a pair goes first alternates: a neighbour's burst then
  // favours neither side.
  for (int r = 0; r < 2 * kRepeats; ++r) {
    const bool with_key = r % 2 == 1;
    if (with_key) setenv(mrsim::kKeyFileEnv, key.c_str(), 1);
    (with_key ? piped_signed : piped)
        .push_back(LcmLoop(path, duration, 7903, dir.string(), 1).wall);
    unsetenv(mrsim::kKeyFileEnv);
    (with_key ? loud_signed : loud)
        .push_back(ServerRun(path, duration / 4, true, 7903,
                             with_key ? auth : mrsim::AuthConfig{})
                       .wall);
  }
  // What one signature costs: a state-sized message, signed 20,000 times.
  {
    mrsim::Physics physics(scenario);
    const mrsim::robot_state_t msg =
        mrsim::ToRobotStateMessage(physics.ReadRobotState(0), 1);
    std::vector<uint8_t> bytes(msg.getEncodedSize()), out;
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    mrsim::MessageAuth signer(auth.key);
    const int n = 20000;
    const auto start = Clock::now();
    for (int i = 0; i < n; ++i) {
      signer.Sign("MRSIM_STATE_snake", bytes.data(), bytes.size(), i, &out);
    }
    std::cout << "BENCH signed_sign_us "
              << Seconds(Clock::now() - start) / n * 1e6 << " us ("
              << bytes.size() << "-byte state)" << std::endl;
  }
  std::cout << "signed: pipelined lockstep " << Best(piped_signed)
            << " sim s/s with a key, " << Best(piped) << " without\n";
  std::cout << "BENCH signed_lockstep_ratio "
            << Best(piped_signed) / Best(piped) << " x" << std::endl;
  std::cout << "signed: publishing " << Best(loud_signed)
            << " sim s/s with a key, " << Best(loud) << " without\n";
  std::cout << "BENCH signed_publish_ratio " << Best(loud_signed) / Best(loud)
            << " x" << std::endl;
  std::filesystem::remove_all(dir);
  return 0;
}

int RunBench() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("mrsim_bench_lcm_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  mrsim::Scenario scenario;
  mrsim::ChainOptions chain;
  chain.modules = 11;
  scenario.robots.push_back(mrsim::MakeChain(chain));
  scenario.settings.timestep = 0.002;
  const std::string path = (dir / "snake11.xml").string();
  mrsim::WriteScenarioFile(scenario, path);

  // (a) lockstep over LCM vs in one process; best of kRepeats each, so a
  // neighbour's burst on a shared machine does not decide the ratio.
  const double duration = 20.0;
  // Strict lockstep and pipelined lockstep (--actuation-delay 1, the
  // answer to state k acts from period k+1) against the same baseline.
  // A delay of 2 as well: it hides a round trip longer than one period's
  // physics (docs/sim.md).
  // And both with --no-spin: the send thread asleep between states.
  std::vector<double> local, remote, piped, piped2, local_cpu, remote_cpu,
      piped_cpu, remote_sleep, piped_sleep, piped_signed;
  // (d): mrsim-sim and the controller sign with this key when
  // MRSIM_KEY_FILE names it.
  const std::string key = (dir / "bench.key").string();
  mrsim::WriteKeyFile(key);
  for (int r = 0; r < kRepeats; ++r) {
    const Pace l = LocalLoop(path, duration, dir.string());
    const Pace x = LcmLoop(path, duration, 7900, dir.string(), 0);
    const Pace p = LcmLoop(path, duration, 7900, dir.string(), 1);
    const Pace p2 = LcmLoop(path, duration, 7900, dir.string(), 2);
    const Pace xs = LcmLoop(path, duration, 7900, dir.string(), 0, false);
    const Pace ps = LcmLoop(path, duration, 7900, dir.string(), 1, false);
    remote_sleep.push_back(xs.wall);
    piped_sleep.push_back(ps.wall);
    setenv(mrsim::kKeyFileEnv, key.c_str(), 1);
    piped_signed.push_back(LcmLoop(path, duration, 7900, dir.string(), 1).wall);
    unsetenv(mrsim::kKeyFileEnv);
    piped2.push_back(p2.wall);
    local.push_back(l.wall);
    remote.push_back(x.wall);
    piped.push_back(p.wall);
    local_cpu.push_back(l.cpu);
    remote_cpu.push_back(x.cpu);
    piped_cpu.push_back(p.cpu);
  }
  std::cout << "lockstep: in-process " << Best(local) << " sim s/s, over LCM "
            << Best(remote) << " sim s/s strict, " << Best(piped)
            << " sim s/s pipelined (per CPU s of all processes: "
            << Best(local_cpu) << " vs " << Best(remote_cpu) << " and "
            << Best(piped_cpu) << ")\n";
  std::cout << "BENCH lockstep_ratio " << Best(remote) / Best(local) << " x"
            << std::endl;
  std::cout << "BENCH lockstep_ratio_cpu " << Best(remote_cpu) / Best(local_cpu)
            << " x" << std::endl;
  std::cout << "BENCH lockstep_pipelined_ratio " << Best(piped) / Best(local)
            << " x" << std::endl;
  std::cout << "BENCH lockstep_pipelined2_ratio " << Best(piped2) / Best(local)
            << " x" << std::endl;
  std::cout << "BENCH lockstep_ratio_nospin "
            << Best(remote_sleep) / Best(local) << " x" << std::endl;
  std::cout << "BENCH lockstep_pipelined_ratio_nospin "
            << Best(piped_sleep) / Best(local) << " x" << std::endl;
  std::cout << "BENCH lockstep_pipelined_ratio_cpu "
            << Best(piped_cpu) / Best(local_cpu) << " x" << std::endl;
  std::cout << "signed: pipelined lockstep " << Best(piped_signed)
            << " sim s/s with a key, " << Best(piped) << " without\n";
  std::cout << "BENCH signed_lockstep_ratio "
            << Best(piped_signed) / Best(piped) << " x" << std::endl;

  // (b) fast clock with and without 100 Hz state publishing.
  // The snake lies still (no controller), the heaviest contact load.
  std::vector<double> quiet, loud, quiet_cpu, loud_cpu, loud_signed;
  const mrsim::AuthConfig auth = mrsim::LoadAuthConfig(key, false);
  for (int r = 0; r < kRepeats; ++r) {
    const Pace q = ServerRun(path, duration / 4, false, 7901);
    const Pace l = ServerRun(path, duration / 4, true, 7901);
    loud_signed.push_back(ServerRun(path, duration / 4, true, 7901, auth).wall);
    quiet.push_back(q.wall);
    loud.push_back(l.wall);
    quiet_cpu.push_back(q.cpu);
    loud_cpu.push_back(l.cpu);
  }
  std::cout << "fast clock: no publishing " << Best(quiet)
            << " sim s/s, publishing " << Best(loud)
            << " sim s/s (per CPU s: " << Best(quiet_cpu) << " vs "
            << Best(loud_cpu) << ")\n";
  std::cout << "BENCH publish_ratio " << Best(loud) / Best(quiet) << " x"
            << std::endl;
  std::cout << "BENCH publish_ratio_cpu " << Best(loud_cpu) / Best(quiet_cpu)
            << " x" << std::endl;
  std::cout << "signed: publishing " << Best(loud_signed)
            << " sim s/s with a key, " << Best(loud) << " without\n";
  std::cout << "BENCH signed_publish_ratio " << Best(loud_signed) / Best(loud)
            << " x" << std::endl;

  // (c) round trips.
  {
    lcm::LCM lcm(Url(7902));
    Pong pong;
    lcm.subscribe("BENCH_STATE_PONG", &Pong::OnState, &pong);
    lcm.subscribe("BENCH_RAW_PONG", &Pong::OnRaw, &pong);
    Child echo({SelfPath(), "--echo", Url(7902)});
    mrsim::Physics physics(scenario);
    physics.Step(50);
    const mrsim::robot_state_t msg =
        mrsim::ToRobotStateMessage(physics.ReadRobotState(0), 1);
    // Wait until the echo answers at all.
    const uint64_t hello = 1;
    for (int i = 0; i < 100 && !pong.got; ++i) {
      lcm.publish("BENCH_RAW_PING", &hello, sizeof(hello));
      mrsim::HandleFor(lcm, 50);
    }
    const int n = 2000;
    const double state_us = RoundTrip(lcm, pong, true, msg, n);
    const double raw_us = RoundTrip(lcm, pong, false, msg, n);
    std::cout << "state message " << msg.getEncodedSize() << " bytes\n";
    std::cout << "BENCH lcm_rtt_us " << state_us << " us" << std::endl;
    std::cout << "BENCH raw_rtt_us " << raw_us << " us" << std::endl;
  }
  std::filesystem::remove_all(dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 3 && std::strcmp(argv[1], "--controller") == 0) {
      return RunController(argv[2]);
    }
    if (argc == 4 && std::strcmp(argv[1], "--inprocess") == 0) {
      return RunInProcess(argv[2], argv[3]);
    }
    if (argc == 3 && std::strcmp(argv[1], "--echo") == 0) {
      return RunEcho(argv[2]);
    }
    if (argc == 2 && std::strcmp(argv[1], "--signed") == 0) {
      return RunSignedBench();
    }
    return RunBench();
  } catch (const std::exception& e) {
    std::cerr << "bench_lcm: " << e.what() << "\n";
    return 1;
  }
}

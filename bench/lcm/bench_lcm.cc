// bench_lcm: what LCM costs the simulator, measured in one run.
//  (a) closed-loop lockstep over LCM (mrsim-sim + a controller process,
//      100 Hz control, 2 ms physics step), strict and pipelined
//      (--actuation-delay 1, and 2; strict and delay 1 also --no-spin),
//      vs the same loop in one process; the headline (pipelined, delay 1)
//      in many more rounds of its own;
//  (b) mrsim-sim's server publishing state at 100 Hz vs not publishing
//      (fast clock);
//  (c) round trip of a state-sized robot_state_t through encode/decode and a
//      typed handler vs a bare ping-pong of an 8-byte raw message;
//  (d) signed messages (--key-file): pipelined lockstep and (b)'s publishing
//      with a key over the same without.
// Every ratio is the median of interleaved rounds (each round runs every
// variant once, the order reversed every other round), printed with its
// spread (bench/common/paired_ratio.h); a ratio over the in-process loop
// from the rounds in the machine's fast speed state only
// (bench/common/speed_states.h). LCM ports 7900-7909. Prints BENCH lines
// (bench/run); --headline only lockstep_pipelined_ratio, --signed only (d).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "bench/common/paired_ratio.h"
#include "bench/common/sim_report.h"
#include "bench/common/speed_states.h"
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
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/sim_process/sim_server.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRate = 100.0;
// Rounds of short runs (10 sim s, a few tenths of a wall second each):
// single lockstep runs swing by half with where the scheduler puts the
// two processes, so a ratio needs many pairs; the best of three runs of
// 20 s (as before) moved by 10-40 % between runs. Shorter runs read 2-4 %
// faster in the median (README), alike for both sides of a ratio. With
// 24 rounds two back-to-back runs on a quiet machine agreed within 2 %,
// but runs minutes apart moved 7 %: 48 halve the median's variance.
constexpr int kRounds = 48;
constexpr double kDuration = 10.0;  // sim s of a lockstep run
// The headline, lockstep_pipelined_ratio, in rounds of its own: 600 pairs
// of 4 sim s, about three minutes. On these VMs one thread runs in one of
// two speed states (the in-process loop at about 58 or 91 sim s per s) and
// the loop over LCM, which waits on round trips, slows less in the slow
// one, so single pair ratios fall in two groups (about 0.65 and 0.85) and
// their median jumped with the share of fast rounds (0.739, 0.770, 0.694,
// 0.681 in four runs in a row, 30-91 % fast). Every ratio over the
// in-process loop is therefore taken in the fast state only (0.657, 0.648,
// 0.656, 0.666 in the same runs, 0.655 and 0.665 in two full runs back to
// back; bench/common/speed_states.h), the other state's and all rounds'
// medians printed beside it.
constexpr int kHeadlineRounds = 600;
constexpr double kHeadlineDuration = 4.0;

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

// Sim seconds per wall second of mrsim-sim + controller in lockstep are
// as mrsim-sim reports them (from its first period to its last,
// ReadRealTimeFactor). The bench itself stays off the LCM network
// meanwhile: on udpm every member of the group wakes for every message,
// and a third process would slow the loop.

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
  return {mrsim::ReadRealTimeFactor(out), duration / cpu};
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
  return {mrsim::ReadRealTimeFactor(out), duration / cpu};
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

// The ratio of two variants of the same rounds, printed with its spread.
void Ratio(const std::string& name, const std::vector<double>& a,
           const std::vector<double>& b, const std::string& what) {
  mrsim::PrintBench(name, mrsim::SummarizePairs(a, b), "x", what);
}

// A ratio over the in-process loop `b`, from the rounds in the machine's
// fast state (`states`, found from the in-process loop's speed): a comment
// says how the rounds split and what the slow state and all rounds gave.
// `a` and `b` may be per CPU s; the states are per round either way.
void FastStateRatio(const std::string& name, const std::vector<double>& a,
                    const std::vector<double>& b,
                    const mrsim::SpeedStates& states, const std::string& what) {
  const mrsim::PairedRatio all = mrsim::SummarizePairs(a, b);
  std::ostringstream note;
  note << "# " << name << ": ";
  if (states.two_states) {
    std::vector<bool> slow(states.fast.size());
    for (size_t i = 0; i < slow.size(); ++i) slow[i] = !states.fast[i];
    const mrsim::PairedRatio s =
        mrsim::SummarizePairs(mrsim::Select(a, slow), mrsim::Select(b, slow));
    note << std::fixed << std::setprecision(1)
         << "two speed states (in-process " << states.slow_median << " | "
         << states.fast_median << " sim s/s, split at " << states.threshold
         << std::setprecision(3) << ", separability " << states.separability
         << "): " << states.fast_count() << " of " << states.fast.size()
         << " rounds fast; median ratio fast below, slow " << s.median
         << ", all " << all.median;
  } else {
    note << "one speed state: all " << states.fast.size() << " rounds";
  }
  std::cout << note.str() << std::endl;
  Ratio(name, mrsim::Select(a, states.fast), mrsim::Select(b, states.fast),
        what);
}

// Signing only adds work: a median above 1 is noise, printed as 1.
void CostRatio(const std::string& name, const std::vector<double>& a,
               const std::vector<double>& b, const std::string& what) {
  mrsim::PrintBenchAtMost(name, mrsim::SummarizePairs(a, b), 1.0, "x", what);
}

// The headline's own rounds: pipelined beside in-process, nothing else.
std::vector<std::vector<double>> HeadlineRounds(const std::string& path,
                                                const std::string& tmp) {
  return mrsim::RunInterleaved(
      {[&] { return LcmLoop(path, kHeadlineDuration, 7900, tmp, 1).wall; },
       [&] { return LocalLoop(path, kHeadlineDuration, tmp).wall; }},
      kHeadlineRounds);
}

void PrintHeadline(const std::vector<std::vector<double>>& h) {
  FastStateRatio("lockstep_pipelined_ratio", h[0], h[1],
                 mrsim::FindSpeedStates(h[1]),
                 "sim s/s, over LCM / in-process (" +
                     std::to_string(kHeadlineRounds) + " rounds of its own)");
}

// A folder of its own under the temporary directory, removed with
// everything in it when the run ends, by an error too.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() /
              (prefix + std::to_string(getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The 11-module snake every loop runs, written into `dir`.
std::string WriteSnake(const std::filesystem::path& dir) {
  mrsim::Scenario scenario;
  mrsim::ChainOptions chain;
  chain.modules = 11;
  scenario.robots.push_back(mrsim::MakeChain(chain));
  scenario.settings.timestep = 0.002;
  const std::string path = (dir / "snake11.xml").string();
  mrsim::WriteScenarioFile(scenario, path);
  return path;
}

// --headline: only lockstep_pipelined_ratio.
int RunHeadlineBench() {
  const ScratchDir scratch("mrsim_bench_lcm_headline_");
  const std::filesystem::path& dir = scratch.path();
  PrintHeadline(HeadlineRounds(WriteSnake(dir), dir.string()));
  return 0;
}

// --signed: only (d), the two signed figures, in rounds of their own.
int RunSignedBench() {
  const ScratchDir scratch("mrsim_bench_lcm_signed_");
  const std::filesystem::path& dir = scratch.path();
  const std::string path = WriteSnake(dir);
  const mrsim::Scenario scenario = mrsim::ReadScenarioFile(path);
  const std::string key = (dir / "bench.key").string();
  mrsim::WriteKeyFile(key);
  const mrsim::AuthConfig auth = mrsim::LoadAuthConfig(key, false);
  const double duration = kDuration;
  // Rounds of the four, the order reversed every other round: a
  // neighbour's burst then favours neither side.
  auto with_key = [&](auto measure) {
    return [&key, measure] {
      setenv(mrsim::kKeyFileEnv, key.c_str(), 1);
      const double v = measure();
      unsetenv(mrsim::kKeyFileEnv);
      return v;
    };
  };
  auto piped = [&] {
    return LcmLoop(path, duration, 7903, dir.string(), 1).wall;
  };
  auto loud = [&](const mrsim::AuthConfig& a) {
    return [&path, duration, a] {
      return ServerRun(path, duration / 4, true, 7903, a).wall;
    };
  };
  const auto v = mrsim::RunInterleaved(
      {piped, with_key(piped), loud({}), loud(auth)}, kRounds);
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
  CostRatio("signed_lockstep_ratio", v[1], v[0],
            "pipelined lockstep sim s/s, key / none");
  CostRatio("signed_publish_ratio", v[3], v[2],
            "publishing sim s/s, key / none");
  return 0;
}

int RunBench() {
  const ScratchDir scratch("mrsim_bench_lcm_");
  const std::filesystem::path& dir = scratch.path();
  const std::string path = WriteSnake(dir);
  const mrsim::Scenario scenario = mrsim::ReadScenarioFile(path);

  // (a) lockstep over LCM vs in one process, in rounds of every variant.
  const double duration = kDuration;
  // Strict lockstep and pipelined lockstep (--actuation-delay 1, the
  // answer to state k acts from period k+1) against the same baseline.
  // A delay of 2 as well: it hides a round trip longer than one period's
  // physics (docs/sim.md).
  // And both with --no-spin: the send thread asleep between states.
  // (d): mrsim-sim and the controller sign with this key when
  // MRSIM_KEY_FILE names it.
  const std::string key = (dir / "bench.key").string();
  mrsim::WriteKeyFile(key);
  const std::string tmp = dir.string();
  std::vector<double> local_cpu, remote_cpu, piped_cpu;
  // A loop's sim s per wall s; its sim s per CPU s into `cpu` if given.
  auto lcm_loop = [&](int delay, bool spin, std::vector<double>* cpu) {
    return [&, delay, spin, cpu] {
      const Pace p = LcmLoop(path, duration, 7900, tmp, delay, spin);
      if (cpu != nullptr) cpu->push_back(p.cpu);
      return p.wall;
    };
  };
  auto local = [&] {
    const Pace p = LocalLoop(path, duration, tmp);
    local_cpu.push_back(p.cpu);
    return p.wall;
  };
  auto signed_piped = [&] {
    setenv(mrsim::kKeyFileEnv, key.c_str(), 1);
    const double wall = LcmLoop(path, duration, 7900, tmp, 1).wall;
    unsetenv(mrsim::kKeyFileEnv);
    return wall;
  };
  // Each headline's two sides run next to each other in every round
  // (pipelined beside in-process and beside signed), whichever order.
  const auto a = mrsim::RunInterleaved(
      {signed_piped, lcm_loop(1, true, &piped_cpu), local,
       lcm_loop(0, true, &remote_cpu), lcm_loop(1, false, nullptr),
       lcm_loop(0, false, nullptr), lcm_loop(2, true, nullptr)},
      kRounds);
  const auto& [piped_signed, piped, in_process, remote, piped_sleep,
               remote_sleep, piped2] =
      std::tie(a[0], a[1], a[2], a[3], a[4], a[5], a[6]);
  const auto h = HeadlineRounds(path, tmp);
  std::cout << "# lockstep, " << kRounds << " rounds of " << duration
            << " sim s: medians in-process " << mrsim::Median(in_process)
            << " sim s/s, over LCM " << mrsim::Median(remote) << " strict, "
            << mrsim::Median(piped)
            << " pipelined (per CPU s of all processes: "
            << mrsim::Median(local_cpu) << " vs " << mrsim::Median(remote_cpu)
            << " and " << mrsim::Median(piped_cpu) << ")" << std::endl;
  const std::string over_local = "sim s/s, over LCM / in-process";
  const std::string per_cpu = "sim s per CPU s, over LCM / in-process";
  const mrsim::SpeedStates states = mrsim::FindSpeedStates(in_process);
  FastStateRatio("lockstep_ratio", remote, in_process, states, over_local);
  FastStateRatio("lockstep_ratio_cpu", remote_cpu, local_cpu, states, per_cpu);
  PrintHeadline(h);
  FastStateRatio("lockstep_pipelined2_ratio", piped2, in_process, states,
                 over_local);
  FastStateRatio("lockstep_ratio_nospin", remote_sleep, in_process, states,
                 over_local);
  FastStateRatio("lockstep_pipelined_ratio_nospin", piped_sleep, in_process,
                 states, over_local);
  FastStateRatio("lockstep_pipelined_ratio_cpu", piped_cpu, local_cpu, states,
                 per_cpu);
  CostRatio("signed_lockstep_ratio", piped_signed, piped,
            "pipelined lockstep sim s/s, key / none");

  // (b) fast clock with and without 100 Hz state publishing.
  // The snake lies still (no controller), the heaviest contact load.
  const mrsim::AuthConfig auth = mrsim::LoadAuthConfig(key, false);
  std::vector<double> quiet_cpu, loud_cpu;
  auto server = [&](bool publish, const mrsim::AuthConfig& with,
                    std::vector<double>* cpu) {
    return [&, publish, with, cpu] {
      const Pace p = ServerRun(path, duration / 4, publish, 7901, with);
      if (cpu != nullptr) cpu->push_back(p.cpu);
      return p.wall;
    };
  };
  const auto b = mrsim::RunInterleaved(
      {server(false, {}, &quiet_cpu), server(true, {}, &loud_cpu),
       server(true, auth, nullptr)},
      kRounds);
  std::cout << "# fast clock: medians no publishing " << mrsim::Median(b[0])
            << " sim s/s, publishing " << mrsim::Median(b[1])
            << " (per CPU s: " << mrsim::Median(quiet_cpu) << " vs "
            << mrsim::Median(loud_cpu) << "), signed " << mrsim::Median(b[2])
            << std::endl;
  Ratio("publish_ratio", b[1], b[0], "sim s/s, publishing / not");
  Ratio("publish_ratio_cpu", loud_cpu, quiet_cpu,
        "sim s per CPU s, publishing / not");
  CostRatio("signed_publish_ratio", b[2], b[1],
            "publishing sim s/s, key / none");

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
    if (argc == 2 && std::strcmp(argv[1], "--headline") == 0) {
      return RunHeadlineBench();
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

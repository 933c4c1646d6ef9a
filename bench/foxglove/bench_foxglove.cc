// Benchmark: mrsim-foxglove beside the case study on the realtime clock
// (scenarios/case_study.xml at 100 Hz, as a user watches it), with
// Foxglove's own client library as the clients (tests/foxglove/
// client_check.js count: subscribed to every channel).
//   BENCH foxglove_sim_slowdown <median> x  the simulator's real-time
//       factor with mrsim-foxglove and one client over without, in
//       interleaved pairs (paired_ratio.h); target >= 0.95
//   BENCH foxglove_clients_10 <median> x    with 10 clients, the transform
//       frames each receives over the states the simulator published
//       (median over the clients; _min the worst); target >= 0.9
// Rounds: --rounds N (default 4) of --seconds S sim seconds (default 10),
// or $MRSIM_BENCH_FOXGLOVE_ROUNDS / $MRSIM_BENCH_FOXGLOVE_SECONDS. Needs
// node and tests/foxglove/node_modules (scripts/install_deps.sh).
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/common/paired_ratio.h"
#include "bench/common/sim_report.h"
#include "common/subprocess.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRate = 100.0;
const char* const kUrl = "udpm://239.255.76.67:8125?ttl=0";

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Polls `path` until it holds `text` (a benchmark may poll; tests wait).
void WaitForText(const std::string& path, const std::string& text,
                 double timeout_s) {
  const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (ReadText(path).find(text) == std::string::npos) {
    if (Clock::now() > end) {
      throw std::runtime_error(path + ": no '" + text + "' within " +
                               std::to_string(timeout_s) +
                               " s: " + ReadText(path));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

struct Child {
  Child(const std::vector<std::string>& argv, const std::string& out)
      : path(out), process(argv, mrsim::SpawnOptions::ToFile(out)) {}
  std::string path;
  mrsim::Subprocess process;
};

std::string Client() {
  return std::string(MRSIM_SOURCE_DIR) + "/tests/foxglove/client_check.js";
}

// mrsim-foxglove with `clients` clients subscribed, or nothing when 0.
struct Watchers {
  std::unique_ptr<Child> foxglove;
  std::vector<std::unique_ptr<Child>> clients;

  Watchers(int count, const std::string& dir) {
    if (count == 0) return;
    foxglove = std::make_unique<Child>(
        std::vector<std::string>{MRSIM_FOXGLOVE_BINARY, "--lcm-url", kUrl,
                                 "--port", "0", "--bind", "127.0.0.1"},
        dir + "/foxglove.out");
    WaitForText(foxglove->path, "listening on ws://", 30);
    std::smatch m;
    const std::string out = ReadText(foxglove->path);
    if (!std::regex_search(out, m, std::regex("127\\.0\\.0\\.1:(\\d+)"))) {
      throw std::runtime_error("no port in: " + out);
    }
    const std::string url = "ws://127.0.0.1:" + m[1].str() + "/";
    for (int k = 0; k < count; ++k) {
      clients.push_back(std::make_unique<Child>(
          std::vector<std::string>{"/usr/bin/env", "node", Client(), "count",
                                   url, "foxglove.websocket.v1"},
          dir + "/client" + std::to_string(k) + ".out"));
    }
    for (auto& c : clients) WaitForText(c->path, "subscribed", 60);
  }

  // Each client's frames of robot transforms (one per state).
  std::vector<double> Stop() {
    std::vector<double> frames;
    for (auto& c : clients) {
      c->process.Signal(SIGTERM);
      c->process.Wait(30);
      std::smatch m;
      const std::string out = ReadText(c->path);
      frames.push_back(
          std::regex_search(out, m, std::regex("\"robot_tf\":(\\d+)"))
              ? std::stod(m[1].str())
              : 0.0);
    }
    if (foxglove) foxglove->process.Stop(10);
    return frames;
  }
};

// The case study's real-time factor with `clients` Foxglove clients
// watching (0: no mrsim-foxglove at all); `frames` gets each client's
// transform frames.
double Round(int clients, double seconds, std::vector<double>* frames) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "bench_foxglove").string();
  std::filesystem::create_directories(dir);
  Watchers watchers(clients, dir);
  {
    Child sim({MRSIM_SIM_BINARY,
               std::string(MRSIM_SOURCE_DIR) + "/scenarios/case_study.xml",
               "--lcm-url", kUrl, "--clock", "realtime", "--rate", "100",
               "--duration", std::to_string(seconds)},
              dir + "/sim.out");
    if (sim.process.Wait(seconds * 10 + 60) != 0) {
      throw std::runtime_error("mrsim-sim failed: " + ReadText(sim.path));
    }
  }
  const std::vector<double> got = watchers.Stop();
  if (frames != nullptr) *frames = got;
  return mrsim::ReadRealTimeFactor(dir + "/sim.out");
}

double Setting(int argc, char** argv, const char* flag, const char* env,
               double fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == flag) return std::stod(argv[i + 1]);
  }
  const char* v = std::getenv(env);
  return v != nullptr ? std::stod(v) : fallback;
}

int Run(int argc, char** argv) {
  if (std::system("node --version > /dev/null 2>&1") != 0 ||
      !std::filesystem::exists(std::string(MRSIM_SOURCE_DIR) +
                               "/tests/foxglove/node_modules")) {
    std::fprintf(stderr,
                 "bench_foxglove: needs node and tests/foxglove/node_modules "
                 "(scripts/install_deps.sh)\n");
    return 1;
  }
  const int rounds = static_cast<int>(
      Setting(argc, argv, "--rounds", "MRSIM_BENCH_FOXGLOVE_ROUNDS", 4));
  const double seconds =
      Setting(argc, argv, "--seconds", "MRSIM_BENCH_FOXGLOVE_SECONDS", 10);
  const auto rtf =
      mrsim::RunInterleaved({[&] { return Round(1, seconds, nullptr); },
                             [&] { return Round(0, seconds, nullptr); }},
                            rounds);
  mrsim::PrintBench("foxglove_sim_slowdown",
                    mrsim::SummarizePairs(rtf[0], rtf[1]), "x",
                    "case study real-time factor, with mrsim-foxglove and "
                    "one client / without");
  std::vector<double> frames;
  Round(10, seconds, &frames);
  std::vector<double> ratios;
  double worst = 1e9;
  for (const double f : frames) {
    ratios.push_back(f / (seconds * kRate));
    worst = std::min(worst, ratios.back());
  }
  std::printf("BENCH foxglove_clients_10 %.3f x\n", mrsim::Median(ratios));
  std::printf("BENCH foxglove_clients_10_min %.3f x\n", worst);
  std::fprintf(stderr,
               "bench_foxglove: %d pairs of %.0f sim s; 10 clients: transform "
               "frames over the %.0f states published, per client\n",
               rounds, seconds, seconds * kRate);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_foxglove: %s\n", e.what());
    return 1;
  }
}

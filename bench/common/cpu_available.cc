#include "bench/common/cpu_available.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <thread>

namespace mrsim {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A unit of work no compiler can shorten (xorshift-multiply, each step
// depends on the last): about 2 ns a step on a 2020s core.
__attribute__((noinline)) std::uint64_t Spin(std::uint64_t x, int n) {
  for (int i = 0; i < n; ++i) {
    x ^= x >> 29;
    x *= 0xbf58476d1ce4e5b9ULL;
  }
  // Spin is pure, so without this the compiler may move the call past the
  // clock read that is meant to time it.
  asm volatile("" : "+r"(x)::"memory");
  return x;
}

constexpr int kChunk = 200000;  // steps between clock reads (~0.4 ms)

// Steps per second of a core we have to ourselves, from 20 short runs:
// the 4th fastest, so runs the scheduler interrupted are left out, and so
// is a run timed by a clock that glitched (seen in sandboxes, where a run
// of ~1 ms was once timed at 20 ns). Clocks are read rarely: in some
// sandboxes a clock read is a slow system call.
double StepsPerSecond(std::uint64_t& sink) {
  std::vector<double> rates;
  for (int trial = 0; trial < 20; ++trial) {
    const auto t0 = Clock::now();
    sink = Spin(sink, kChunk * 3);
    const double t = Since(t0);
    if (t > 0) rates.push_back(kChunk * 3 / t);
  }
  std::sort(rates.begin(), rates.end(), std::greater<double>());
  return rates.empty() ? 0 : rates[std::min<size_t>(3, rates.size() - 1)];
}

// Spins in `n` child processes at once for `seconds` of wall time; returns
// the chunks per second each managed. Processes, not threads: the
// scheduler shares CPU between process groups, so on a busy machine more
// threads of one process gain little while more processes (like farm
// workers) each get their own share.
std::vector<double> SpinInProcesses(int n, double seconds) {
  std::vector<double> rates;
  std::vector<std::pair<pid_t, int>> children;
  for (int c = 0; c < n; ++c) {
    int fds[2];
    if (pipe(fds) != 0) continue;
    const pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      std::uint64_t x = static_cast<std::uint64_t>(c) + 1;
      long chunks = 0;
      const auto t0 = Clock::now();
      double elapsed = 0;
      while (elapsed < seconds) {
        x = Spin(x, kChunk);
        ++chunks;
        elapsed = Since(t0);
      }
      const double rate = chunks / elapsed;
      if (x == 42) std::fputs("", stderr);  // keep the work
      if (write(fds[1], &rate, sizeof rate) != sizeof rate) _exit(1);
      _exit(0);
    }
    close(fds[1]);
    if (pid < 0) {
      close(fds[0]);
      continue;
    }
    children.emplace_back(pid, fds[0]);
  }
  for (const auto& [pid, fd] : children) {
    double rate = 0;
    if (read(fd, &rate, sizeof rate) == sizeof rate) rates.push_back(rate);
    close(fd);
    int status = 0;
    waitpid(pid, &status, 0);
  }
  return rates;
}

}  // namespace

CpuAvailability MeasureCpuAvailable(double seconds) {
  CpuAvailability cpu;
  cpu.cores_online =
      static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  std::uint64_t sink = 1;
  const double rate = StepsPerSecond(sink) / kChunk;  // chunks per second
  for (double r : SpinInProcesses(cpu.cores_online, seconds)) {
    const double share = std::min(1.0, r / rate);
    cpu.per_core.push_back(share);
    cpu.cores += share;
  }
  const std::vector<double> alone = SpinInProcesses(1, seconds);
  if (!alone.empty()) cpu.one_thread = std::min(1.0, alone[0] / rate);
  if (sink == 42) std::fputs("", stderr);  // keep the work
  return cpu;
}

double CpuAvailability::TwoOverOne() const {
  if (one_thread <= 0) return 2.0;
  return std::min(2.0, cores / one_thread);
}

std::string FormatCpuAvailable(const CpuAvailability& cpu) {
  std::string per_core;
  for (double share : cpu.per_core) {
    char buf[32];
    std::snprintf(buf, sizeof buf, " %.2f", share);
    per_core += buf;
  }
  char out[256];
  std::snprintf(out, sizeof out,
                "# cpu: %d cores online, share of each we got over a "
                "calibrated 1 s spin:%s; one thread alone got %.2f\n"
                "BENCH cpu_available %.2f cores\n",
                cpu.cores_online, per_core.c_str(), cpu.one_thread, cpu.cores);
  return out;
}

}  // namespace mrsim

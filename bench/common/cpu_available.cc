#include "bench/common/cpu_available.h"

#include <pthread.h>
#include <sched.h>
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

}  // namespace

CpuAvailability MeasureCpuAvailable(double seconds) {
  CpuAvailability cpu;
  cpu.cores_online =
      static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  std::uint64_t sink = 1;
  const double rate = StepsPerSecond(sink) / kChunk;  // chunks per second
  std::vector<long> chunks(cpu.cores_online, 0);
  std::vector<double> wall(cpu.cores_online, 0);
  std::atomic<std::uint64_t> total_sink{0};
  std::vector<std::thread> threads;
  for (int c = 0; c < cpu.cores_online; ++c) {
    threads.emplace_back([&, c] {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(c, &set);
      pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
      std::uint64_t x = c + 1;
      const auto t0 = std::chrono::steady_clock::now();
      double elapsed = 0;
      while (elapsed < seconds) {
        x = Spin(x, kChunk);
        ++chunks[c];
        elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                .count();
      }
      wall[c] = elapsed;
      total_sink += x;
    });
  }
  for (std::thread& t : threads) t.join();
  for (int c = 0; c < cpu.cores_online; ++c) {
    const double share = std::min(1.0, chunks[c] / (rate * wall[c]));
    cpu.per_core.push_back(share);
    cpu.cores += share;
  }
  if (total_sink == 42 && sink == 42) std::fputs("", stderr);  // keep the work
  return cpu;
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
                "calibrated 1 s spin:%s\nBENCH cpu_available %.2f cores\n",
                cpu.cores_online, per_core.c_str(), cpu.cores);
  return out;
}

}  // namespace mrsim

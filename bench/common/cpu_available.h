// How much CPU this machine gives us right now, for benchmarks whose
// figures depend on it (a parallel speed-up cannot exceed the cores that are
// actually free on a shared machine).
#pragma once

#include <string>
#include <vector>

namespace mrsim {

struct CpuAvailability {
  double cores = 0.0;            // sum over the cores, each in [0, 1]
  std::vector<double> per_core;  // share each of the threads got
  int cores_online = 0;
  // What one thread alone got, in cores. On a machine where
  // many processes compete, the scheduler gives each runnable thread a fair
  // share, so two threads get about twice what one gets even when `cores`
  // is far below 2.
  double one_thread = 0.0;  // (measured in one process)
  // min(2, cores / one_thread): the speed-up two processes can reach over
  // one right now.
  double TwoOverOne() const;
};

// A calibrated spin: first the work one thread does per second of its own
// CPU time, then one thread per core (all at once, not pinned) spins for
// `seconds` of wall time; each thread's share is the work it did over what a
// whole core would have done. Other load, steal time and throttling all show up
// as less.
CpuAvailability MeasureCpuAvailable(double seconds = 1.0);

// "BENCH cpu_available 1.93 cores" plus a comment line with each core.
std::string FormatCpuAvailable(const CpuAvailability& cpu);

}  // namespace mrsim

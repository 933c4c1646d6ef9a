// How much CPU this machine gives us right now, for benchmarks whose
// figures depend on it (a parallel speed-up cannot exceed the cores that are
// actually free on a shared machine).
#pragma once

#include <string>
#include <vector>

namespace mrsim {

struct CpuAvailability {
  double cores = 0.0;            // sum over the cores, each in [0, 1]
  std::vector<double> per_core;  // fraction of each core we got
  int cores_online = 0;
};

// A calibrated spin: first the work one thread does per second of its own
// CPU time, then one thread pinned to each core spins for `seconds` of wall
// time; each core's share is the work it did over what a whole core would
// have done. Other load, steal time and throttling all show up as less.
CpuAvailability MeasureCpuAvailable(double seconds = 1.0);

// "BENCH cpu_available 1.93 cores" plus a comment line with each core.
std::string FormatCpuAvailable(const CpuAvailability& cpu);

}  // namespace mrsim

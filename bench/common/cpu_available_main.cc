// Prints "BENCH cpu_available <cores> cores" for the machine right now;
// bench/run prints it before each benchmark so every figure carries the CPU
// it was measured with.
#include <cstdio>

#include "bench/common/cpu_available.h"

int main() {
  std::fputs(mrsim::FormatCpuAvailable(mrsim::MeasureCpuAvailable()).c_str(),
             stdout);
  return 0;
}

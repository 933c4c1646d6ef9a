// The one seeded random source of an optimisation run. std::mt19937_64's
// output sequence is fixed by the standard; the distributions are written
// here because std:: distributions differ between standard libraries.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace mrsim {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  std::uint64_t Next() { return engine_(); }
  // Uniform in [0, 1) with 53 random bits.
  double Uniform01() {
    return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform01(); }
  // Uniform integer in [lo, hi] (inclusive), without modulo bias.
  long long UniformInt(long long lo, long long hi) {
    if (hi <= lo) return lo;
    const std::uint64_t span = static_cast<std::uint64_t>(hi - lo) + 1;
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % span;
    std::uint64_t x = engine_();
    while (x >= limit) x = engine_();
    return lo + static_cast<long long>(x % span);
  }
  bool Bernoulli(double p) { return Uniform01() < p; }
  // Standard normal by Box-Muller; no cached second value, so the engine is
  // the whole state.
  double Normal() {
    const double u1 = 1.0 - Uniform01();  // (0, 1]
    const double u2 = Uniform01();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace mrsim

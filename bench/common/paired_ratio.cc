#include "bench/common/paired_ratio.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mrsim {
namespace {

// The q-quantile of sorted values, interpolating between neighbours.
double Quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0;
  const double at = q * static_cast<double>(sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(at));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] +
         (at - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

std::string Format(const char* format, double a, double b = 0, double c = 0,
                   double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

std::string Lines(const std::string& name, const PairedRatio& r, double value,
                  const std::string& unit, const std::string& what,
                  const std::string& note) {
  std::string out = "# " + name + ": " + std::to_string(r.ratios.size()) +
                    " pairs, ratios " + Format("%.3f-%.3f", r.min, r.max) +
                    Format(" (IQR %.1f%%)", 100 * r.iqr);
  if (!what.empty()) {
    out += "; median " + what + " " +
           Format("%.4g / %.4g", r.median_a, r.median_b);
  }
  out += note + "\n";
  out += "BENCH " + name + Format(" %.3f ", value) + unit + "\n";
  out += "BENCH " + name + "_spread" + Format(" %.1f %%\n", 100 * r.spread);
  // One pair has no spread to show; it is not a figure either.
  if (r.ratios.size() < 2) {
    out += "# " + name + ": " + std::to_string(r.ratios.size()) +
           " pairs: not a reliable figure on this machine right now\n";
  } else if (!(r.spread <= kReliableSpread)) {
    out += "# " + name +
           Format(": spread %.1f%% > %.0f%%", 100 * r.spread,
                  100 * kReliableSpread) +
           ": not a reliable figure on this machine right now\n";
  }
  return out;
}

}  // namespace

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return Quantile(v, 0.5);
}

double RelativeIqr(std::vector<double> v) {
  if (v.size() < 2) return 0;
  std::sort(v.begin(), v.end());
  const double median = Quantile(v, 0.5);
  if (median == 0) return 0;
  return (Quantile(v, 0.75) - Quantile(v, 0.25)) / std::fabs(median);
}

double RelativeMedianInterval(std::vector<double> v) {
  const size_t n = v.size();
  if (n < 2) return 0;
  std::sort(v.begin(), v.end());
  const double median = Quantile(v, 0.5);
  if (median == 0) return 0;
  // Ranks (1-based) of the interval's ends: the number of values below the
  // true median is binomial(n, 1/2), within n/2 -+ 1.96 sqrt(n)/2 95 times
  // in 100.
  const double half = 0.98 * std::sqrt(static_cast<double>(n));
  const double n2 = static_cast<double>(n) / 2;
  const size_t lo = static_cast<size_t>(std::max(1.0, std::floor(n2 - half)));
  const size_t hi = static_cast<size_t>(
      std::min(static_cast<double>(n), std::ceil(n2 + 1 + half)));
  return (v[hi - 1] - v[lo - 1]) / std::fabs(median);
}

PairedRatio SummarizePairs(const std::vector<double>& a,
                           const std::vector<double>& b) {
  if (a.size() != b.size()) {
    throw std::invalid_argument("SummarizePairs: sides of unequal length");
  }
  PairedRatio r;
  r.a = a;
  r.b = b;
  for (size_t i = 0; i < a.size(); ++i) {
    const double ratio = b[i] != 0 ? a[i] / b[i] : NAN;
    if (std::isfinite(ratio)) r.ratios.push_back(ratio);
  }
  if (r.ratios.empty()) return r;
  r.median = Median(r.ratios);
  r.spread = RelativeMedianInterval(r.ratios);
  r.iqr = RelativeIqr(r.ratios);
  const auto [lo, hi] = std::minmax_element(r.ratios.begin(), r.ratios.end());
  r.min = *lo;
  r.max = *hi;
  r.median_a = Median(a);
  r.median_b = Median(b);
  return r;
}

std::vector<std::vector<double>> RunInterleaved(
    const std::vector<std::function<double()>>& measures, int rounds) {
  const size_t n = measures.size();
  std::vector<std::vector<double>> values(n);
  for (int round = 0; round < rounds; ++round) {
    for (size_t step = 0; step < n; ++step) {
      const size_t k = round % 2 == 0 ? step : n - 1 - step;
      values[k].push_back(measures[k]());
    }
  }
  return values;
}

PairedRatio RunPaired(const std::function<double()>& a,
                      const std::function<double()>& b, int pairs) {
  const auto values = RunInterleaved({a, b}, pairs);
  return SummarizePairs(values[0], values[1]);
}

std::string FormatBench(const std::string& name, const PairedRatio& r,
                        const std::string& unit, const std::string& what) {
  return Lines(name, r, r.median, unit, what, "");
}

std::string FormatBenchAtMost(const std::string& name, const PairedRatio& r,
                              double limit, const std::string& unit,
                              const std::string& what) {
  if (r.median <= limit) return Lines(name, r, r.median, unit, what, "");
  return Lines(name, r, limit, unit, what,
               Format("; median %.3f clamped to %.3f", r.median, limit));
}

void PrintBench(const std::string& name, const PairedRatio& r,
                const std::string& unit, const std::string& what) {
  std::fputs(FormatBench(name, r, unit, what).c_str(), stdout);
  std::fflush(stdout);
}

void PrintBenchAtMost(const std::string& name, const PairedRatio& r,
                      double limit, const std::string& unit,
                      const std::string& what) {
  std::fputs(FormatBenchAtMost(name, r, limit, unit, what).c_str(), stdout);
  std::fflush(stdout);
}

}  // namespace mrsim

#include "bench/common/speed_states.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bench/common/paired_ratio.h"

namespace mrsim {
namespace {

// Otsu's separability two states need (speed_states.h): a single state,
// however wide, is one hump, at most flat as a uniform's 0.75.
constexpr double kMinSeparability = 0.75;
// A cluster with fewer than this share of the repeats is a few outliers,
// not a state.
constexpr double kMinShare = 0.1;

}  // namespace

int SpeedStates::fast_count() const {
  return static_cast<int>(std::count(fast.begin(), fast.end(), true));
}

SpeedStates FindSpeedStates(const std::vector<double>& baseline) {
  SpeedStates s;
  s.fast.assign(baseline.size(), true);
  const size_t n = baseline.size();
  if (n < 4) return s;
  std::vector<double> sorted = baseline;
  std::sort(sorted.begin(), sorted.end());
  // Otsu: the split of the sorted values with the largest between-class
  // variance, from running sums.
  std::vector<double> prefix(n + 1, 0);
  for (size_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + sorted[i];
  double best = -1;
  size_t split = 0;
  for (size_t k = 1; k < n; ++k) {
    const double w0 = static_cast<double>(k) / static_cast<double>(n);
    const double m0 = prefix[k] / static_cast<double>(k);
    const double m1 = (prefix[n] - prefix[k]) / static_cast<double>(n - k);
    const double between = w0 * (1 - w0) * (m0 - m1) * (m0 - m1);
    if (between > best) {
      best = between;
      split = k;
    }
  }
  const std::vector<double> lo(sorted.begin(), sorted.begin() + split);
  const std::vector<double> hi(sorted.begin() + split, sorted.end());
  const double min_count = std::max(2.0, kMinShare * static_cast<double>(n));
  if (static_cast<double>(lo.size()) < min_count ||
      static_cast<double>(hi.size()) < min_count) {
    return s;
  }
  const double mean = prefix[n] / static_cast<double>(n);
  double total = 0;
  for (double x : sorted) total += (x - mean) * (x - mean);
  total /= static_cast<double>(n);
  const double separability = total > 0 ? best / total : 0;
  if (!(separability >= kMinSeparability)) return s;
  s.two_states = true;
  s.threshold = (sorted[split - 1] + sorted[split]) / 2;
  s.separability = separability;
  s.slow_median = Median(lo);
  s.fast_median = Median(hi);
  for (size_t i = 0; i < n; ++i) s.fast[i] = baseline[i] > s.threshold;
  return s;
}

std::vector<double> Select(const std::vector<double>& v,
                           const std::vector<bool>& keep) {
  if (v.size() != keep.size()) {
    throw std::invalid_argument("Select: values and mask of unequal length");
  }
  std::vector<double> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (keep[i]) out.push_back(v[i]);
  }
  return out;
}

}  // namespace mrsim

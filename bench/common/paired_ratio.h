// Ratios that hold still on a shared machine: a candidate measured against
// its baseline in interleaved, paired repeats, the median of the pair
// ratios printed with its spread.
//
// Why pairs: a neighbour's build, a frequency change or the scheduler's
// placement moves every measurement taken at the same moment alike, so the
// ratio of two measurements taken back to back keeps still where the
// measurements themselves swing by half. Why the median: one repeat that a
// burst hit cannot move it. Why the order alternates (A B, then B A): a
// load that rises or falls through the run then favours neither side.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace mrsim {

// The statistics of one ratio over paired repeats.
struct PairedRatio {
  double median = 0;  // median of the pair ratios a[i] / b[i]
  // How far the median itself can be trusted: the width of its 95 %
  // confidence interval (distribution-free, between the order statistics
  // n/2 -+ 0.98 sqrt(n) of the pair ratios) over the median. Two runs'
  // medians differ by less than this 99 times in 100, so a spread of 5 %
  // is what "two runs within 5 % of each other" needs. More pairs narrow
  // it as 1 / sqrt(n) even where single pairs scatter widely; with fewer
  // than 11 pairs it is (max - min) / median.
  double spread = 0;
  // The scatter of single pair ratios, (q75 - q25) / median: what one
  // short measurement is worth on this machine right now.
  double iqr = 0;
  double min = 0;  // smallest and largest pair ratio
  double max = 0;
  double median_a = 0;  // median of each side's own values
  double median_b = 0;
  std::vector<double> ratios;  // a[i] / b[i], in measurement order
  std::vector<double> a, b;    // the raw values, in measurement order
};

// Median and spread of a[i] / b[i] over the pairs (a and b the same
// length; pairs with b[i] == 0 or a non-finite ratio are left out).
PairedRatio SummarizePairs(const std::vector<double>& a,
                           const std::vector<double>& b);

// Median of `v` (the mean of the middle two for an even count; 0 if empty).
double Median(std::vector<double> v);

// Relative interquartile range of `v` around its median, linear
// interpolation between order statistics (0 if fewer than 2 values).
double RelativeIqr(std::vector<double> v);

// Width of the distribution-free 95 % confidence interval of the median of
// `v` over the median (0 if fewer than 2 values).
double RelativeMedianInterval(std::vector<double> v);

// Calls each of `measures` once per round, `rounds` times, in forward order
// on even rounds and backward on odd ones (A B C, C B A, ...), and returns
// each one's values in round order: result[k][r] is measures[k] in round r.
// Every value of round r was taken within the same few seconds, so any two
// of them form a pair for SummarizePairs.
std::vector<std::vector<double>> RunInterleaved(
    const std::vector<std::function<double()>>& measures, int rounds);

// RunInterleaved of a and b, summarised as a / b.
PairedRatio RunPaired(const std::function<double()>& a,
                      const std::function<double()>& b, int pairs);

// The spread above which a figure is not to be trusted: two runs of it
// would differ by more than the 5 % a benchmark's target needs to see.
inline constexpr double kReliableSpread = 0.05;

// The lines of one ratio, in this order: a comment with the pairs, the
// extremes, the pairs' IQR and each side's median ("# name: 12 pairs,
// ..."), then
// "BENCH name <median> unit" and "BENCH name_spread <spread %> %", and a
// comment "# name: spread X% > 5%: not a reliable figure on this machine
// right now" when the spread is larger (or there are fewer than 2 pairs).
// `what` names the two sides for the comment, e.g. "safe us / lcm-gen us".
std::string FormatBench(const std::string& name, const PairedRatio& r,
                        const std::string& unit, const std::string& what = "");

// As FormatBench with the value clamped to at most `limit`: an efficiency
// (a speed-up over what the machine allows) cannot exceed 1, so a median
// above it is noise; the comment keeps the unclamped median.
std::string FormatBenchAtMost(const std::string& name, const PairedRatio& r,
                              double limit, const std::string& unit,
                              const std::string& what = "");

// FormatBench to stdout, flushed (a later crash keeps what was measured).
void PrintBench(const std::string& name, const PairedRatio& r,
                const std::string& unit, const std::string& what = "");
void PrintBenchAtMost(const std::string& name, const PairedRatio& r,
                      double limit, const std::string& unit,
                      const std::string& what = "");

}  // namespace mrsim

#include "gait_controller/gait_atlas.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gait_controller/gait_presets.h"

namespace mrsim {

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr const char* kClawar2005 =
    "Gonzalez-Gomez & Boemo, CLAWAR 2005 (minimal configurations)";
constexpr const char* kHirose1993 =
    "Hirose 1993 (serpenoid on passive wheels, the ACM)";

AtlasEntry PresetEntry(const Gait& gait) {
  AtlasEntry e;
  e.name = gait.name;
  e.source = "preset";
  e.gait = gait;
  e.trial.chain.pattern = ChainFor(gait);
  return e;
}

AtlasEntry MotionEntry(const std::string& name, const std::string& preset,
                       Motion motion, double strength) {
  AtlasEntry e;
  e.name = name;
  e.source = "motion";
  e.gait = *FindGaitPreset(preset);
  e.trial.motion = motion;
  e.trial.strength = strength;
  e.trial.chain.pattern = ChainFor(e.gait, motion);
  return e;
}

// A minimal configuration: `modules` modules of `pattern`, driven by the
// seven parameters (and the pitch-to-yaw lag).
AtlasEntry MinimalEntry(const std::string& name, int modules,
                        ChainPattern pattern, GaitKind kind,
                        std::vector<double> seven, double lag = 0.0) {
  AtlasEntry e;
  e.name = name;
  e.source = kClawar2005;
  e.gait.name = name;
  e.gait.kind = kind;
  e.gait.parameters = GaitParameters::FromVector(seven);
  e.gait.parameters.pitch_yaw_lag = lag;
  e.trial.chain.modules = modules;
  e.trial.chain.pattern = pattern;
  return e;
}

std::vector<AtlasEntry> MakeEntries() {
  std::vector<AtlasEntry> entries;
  for (const Gait& g : GaitPresets()) entries.push_back(PresetEntry(g));
  // bench_gait's motion commands: the turns on the forward preset turn far
  // more than the turn presets (docs/gait.md).
  entries.push_back(
      MotionEntry("turn-left-0.375", "forward", Motion::kTurnLeft, 0.375));
  entries.push_back(
      MotionEntry("turn-left-1", "forward", Motion::kTurnLeft, 1.0));
  entries.push_back(
      MotionEntry("turn-right-1", "forward", Motion::kTurnRight, 1.0));
  entries.push_back(MotionEntry("backward", "forward", Motion::kBackward, 1.0));
  entries.push_back(
      MotionEntry("sidewind-right", "sidewind", Motion::kSidewindRight, 1.0));
  // Pitch-pitch: two pitch modules, one travelling wave. In phase (0) the
  // body only arches up and down; a phase difference in a window around
  // 110-120 degrees moves it, its sign choosing the direction.
  const double a = 1.0;  // rad
  entries.push_back(MinimalEntry("pp-phase-0", 2, ChainPattern::kPitch,
                                 GaitKind::kLinear, {a, 0, 0, 0, 4, 0, 0}));
  entries.push_back(MinimalEntry("pp-phase-110", 2, ChainPattern::kPitch,
                                 GaitKind::kLinear,
                                 {a, 0, 110 * kDeg, 0, 4, 0, 0}));
  entries.push_back(MinimalEntry("pp-phase-minus-110", 2, ChainPattern::kPitch,
                                 GaitKind::kLinear,
                                 {a, 0, -110 * kDeg, 0, 4, 0, 0}));
  // Pitch-yaw-pitch with its yaw joint still: the 1D sinusoidal gait.
  entries.push_back(MinimalEntry("pyp-straight-110", 3, ChainPattern::kPitchYaw,
                                 GaitKind::kLinear,
                                 {a, 0, 110 * kDeg, 0, 4, 0, 0}));
  // Pitch-yaw-pitch with equal waves, pitch joints in phase and the yaw
  // joint a quarter period later: below 40 degrees of amplitude it shifts
  // sideways, from 60 degrees it rolls.
  entries.push_back(MinimalEntry(
      "pyp-lateral-shift-30", 3, ChainPattern::kPitchYaw, GaitKind::kRoll,
      {30 * kDeg, 30 * kDeg, 0, 0, 4, 0, 0}, M_PI / 2));
  entries.push_back(MinimalEntry(
      "pyp-lateral-rolling-70", 3, ChainPattern::kPitchYaw, GaitKind::kRoll,
      {70 * kDeg, 70 * kDeg, 0, 0, 4, 0, 0}, M_PI / 2));
  // Lateral undulation needs more friction across the body than along it:
  // the serpenoid preset on passive wheels (the preset's own line above
  // runs on MuJoCo's isotropic friction).
  AtlasEntry wheels = PresetEntry(*FindGaitPreset("serpenoid"));
  wheels.name = "serpenoid-wheels";
  wheels.source = kHirose1993;
  wheels.trial.passive_wheels = true;
  entries.push_back(wheels);
  return entries;
}

double Mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double StandardDeviation(const std::vector<double>& v) {
  const double m = Mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return v.size() < 2 ? 0.0 : std::sqrt(s / static_cast<double>(v.size() - 1));
}

std::string RobotName(const GaitTrial& trial) {
  return fmt::format("{} x{}{}", ChainPatternName(trial.chain.pattern),
                     trial.chain.modules,
                     trial.passive_wheels ? " wheels" : "");
}

}  // namespace

const std::vector<AtlasEntry>& AtlasEntries() {
  static const std::vector<AtlasEntry> kEntries = MakeEntries();
  return kEntries;
}

const AtlasEntry& FindAtlasEntry(const std::string& name,
                                 const std::vector<AtlasEntry>& entries) {
  for (const AtlasEntry& e : entries) {
    if (e.name == name) return e;
  }
  throw AtlasTableError("the gait atlas has no entry '" + name + "'");
}

Gait ScaleAmplitudes(Gait gait, double factor) {
  gait.parameters.amplitude_pitch *= factor;
  gait.parameters.amplitude_yaw *= factor;
  for (JointOverride& o : gait.parameters.overrides) {
    if (o.amplitude) *o.amplitude *= factor;
  }
  return gait;
}

std::array<double, kAtlasQuantities> AtlasQuantities(const GaitOutcome& run) {
  return {run.speed, run.drift, run.rise, run.heading_deg, run.roll_deg};
}

std::array<double, kAtlasQuantities> MeasureAtlasValues(const AtlasEntry& entry,
                                                        int samples,
                                                        double scale) {
  std::vector<double> factors;
  if (samples == 1) {
    factors = {1.0};
  } else if (samples == static_cast<int>(kAtlasFactors.size())) {
    factors.assign(kAtlasFactors.begin(), kAtlasFactors.end());
  } else {
    throw std::invalid_argument(
        fmt::format("atlas line {}: samples must be 1 or {}, not {}",
                    entry.name, kAtlasFactors.size(), samples));
  }
  std::array<double, kAtlasQuantities> sum{};
  for (double f : factors) {
    const auto q = AtlasQuantities(
        MeasureGait(ScaleAmplitudes(entry.gait, scale * f), entry.trial));
    for (int i = 0; i < kAtlasQuantities; ++i) sum[i] += q[i];
  }
  for (double& s : sum) s /= static_cast<double>(factors.size());
  return sum;
}

AtlasLine MakeAtlasLine(const AtlasEntry& entry,
                        const std::vector<GaitOutcome>& runs,
                        const AtlasTolerancePolicy& policy) {
  if (runs.size() != kAtlasSpreadFactors.size()) {
    throw std::invalid_argument(
        fmt::format("atlas line {}: {} runs, expected one per factor ({})",
                    entry.name, runs.size(), kAtlasSpreadFactors.size()));
  }
  auto run_at = [&](double factor) -> const GaitOutcome& {
    return runs[std::find(kAtlasSpreadFactors.begin(),
                          kAtlasSpreadFactors.end(), factor) -
                kAtlasSpreadFactors.begin()];
  };
  AtlasLine line;
  line.name = entry.name;
  line.robot = entry.robot.empty() ? RobotName(entry.trial) : entry.robot;
  std::array<std::vector<double>, kAtlasQuantities> values;
  for (const GaitOutcome& r : runs) {
    const auto q = AtlasQuantities(r);
    for (int i = 0; i < kAtlasQuantities; ++i) values[i].push_back(q[i]);
  }
  const auto nominal = AtlasQuantities(run_at(1.0));
  // The mean as MeasureAtlasValues takes it (same order, same bits).
  std::array<double, kAtlasQuantities> mean{};
  for (double f : kAtlasFactors) {
    const auto q = AtlasQuantities(run_at(f));
    for (int i = 0; i < kAtlasQuantities; ++i) mean[i] += q[i];
  }
  for (double& m : mean) m /= static_cast<double>(kAtlasFactors.size());
  bool chaotic = false;
  for (int i = 0; i < kAtlasQuantities; ++i) {
    const double sd = StandardDeviation(values[i]);
    const double floor =
        policy.relative * std::abs(nominal[i]) + policy.floor[i];
    // Would the spread set a single run's tolerance? Then one run says too
    // little and the line is checked by its mean.
    if (policy.k * sd * std::sqrt(2.0) > floor) chaotic = true;
    line.values[i].spread = sd;
  }
  line.samples = chaotic ? static_cast<int>(kAtlasFactors.size()) : 1;
  for (int i = 0; i < kAtlasQuantities; ++i) {
    AtlasValue& v = line.values[i];
    v.value = chaotic ? mean[i] : nominal[i];
    const double floor = policy.relative * std::abs(v.value) + policy.floor[i];
    v.tolerance =
        std::max(policy.k * v.spread * std::sqrt(2.0 / line.samples), floor);
  }
  return line;
}

AtlasLine MeasureAtlasLine(const AtlasEntry& entry,
                           const AtlasTolerancePolicy& policy) {
  std::vector<GaitOutcome> runs;
  for (double f : kAtlasSpreadFactors) {
    runs.push_back(MeasureGait(ScaleAmplitudes(entry.gait, f), entry.trial));
  }
  return MakeAtlasLine(entry, runs, policy);
}

}  // namespace mrsim

// Speed and heading change of every gait preset on the 11-module snake over
// 20 s of flat ground (pitch chain for presets without yaw amplitude,
// pitch-yaw chain otherwise). Prints a table and BENCH lines so later
// changes to the physics or the gaits can be compared.
//
//   bench_gait [--seconds S] [--preset NAME]...
//   bench_gait --gait NAME|FILE [--chain pitch|yaw|pitch-yaw]
//              [--motion M] [--strength S] [--params 7 comma values]
//              [--lag L]      (measures one gait of your own)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_trial.h"

namespace {

using mrsim::Gait;

constexpr int kModules = 11;
constexpr double kSettle = 4.0;  // s: one period of ramp-in, not timed

struct Row {
  std::string preset;
  std::string chain;
  mrsim::GaitOutcome outcome;
  double wall_s = 0;
};

struct Custom {
  std::string chain;  // "" = from the gait
  std::optional<mrsim::Motion> motion;
  double strength = 1.0;
};

// One run through mrsim::MeasureGait (what the gait atlas measures too),
// timed on the wall clock.
Row Measure(const Gait& gait, double seconds, double control_period,
            const Custom& custom = {}) {
  mrsim::GaitTrial trial;
  trial.chain.modules = kModules;
  trial.chain.pattern = mrsim::ChainFor(gait, custom.motion);
  for (auto p : {mrsim::ChainPattern::kPitch, mrsim::ChainPattern::kYaw,
                 mrsim::ChainPattern::kPitchYaw}) {
    if (custom.chain == mrsim::ChainPatternName(p)) trial.chain.pattern = p;
  }
  trial.seconds = seconds;
  trial.settle = kSettle;
  trial.control_period = control_period;
  trial.motion = custom.motion;
  trial.strength = custom.strength;
  const auto start = std::chrono::steady_clock::now();
  Row row;
  row.outcome = mrsim::MeasureGait(gait, trial);
  row.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  row.preset = gait.name;
  row.chain = mrsim::ChainPatternName(trial.chain.pattern);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 20.0;
  std::vector<std::string> only;
  std::optional<Gait> own;
  Custom custom;
  std::optional<std::vector<double>> params;
  std::optional<double> lag;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const bool has_value = i + 1 < argc;
      if (a == "--seconds" && has_value) {
        seconds = std::stod(argv[++i]);
      } else if (a == "--preset" && has_value) {
        only.push_back(argv[++i]);
      } else if (a == "--gait" && has_value) {
        own = mrsim::ResolveGait(argv[++i]);
      } else if (a == "--chain" && has_value) {
        custom.chain = argv[++i];
      } else if (a == "--motion" && has_value) {
        custom.motion = mrsim::ParseMotion(argv[++i]);
        if (!custom.motion) throw std::invalid_argument("unknown motion");
      } else if (a == "--strength" && has_value) {
        custom.strength = std::stod(argv[++i]);
      } else if (a == "--lag" && has_value) {
        lag = std::stod(argv[++i]);
      } else if (a == "--params" && has_value) {
        std::vector<double> v;
        std::stringstream ss(argv[++i]);
        std::string item;
        while (std::getline(ss, item, ',')) v.push_back(std::stod(item));
        params = v;
      } else {
        throw std::invalid_argument("unknown option " + a);
      }
    }
    if (params || lag) {
      if (!own) own = *mrsim::FindGaitPreset("forward");
      if (params) own->parameters = own->parameters.WithVector(*params);
      if (lag) own->parameters.pitch_yaw_lag = *lag;
      own->name = "custom";
    }
    if (own && custom.motion) {
      // The gait goes to the slot the motion uses.
      const mrsim::Motion m = *custom.motion;
      if (m == mrsim::Motion::kSidewindLeft ||
          m == mrsim::Motion::kSidewindRight) {
        own->kind = mrsim::GaitKind::kSidewind;
      } else if (m == mrsim::Motion::kRoll) {
        own->kind = mrsim::GaitKind::kRoll;
      } else if (m != mrsim::Motion::kStop) {
        own->kind = mrsim::GaitKind::kLinear;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "bench_gait: %s\nusage: bench_gait [--seconds S] [--preset "
                 "NAME]... | --gait NAME|FILE [--chain pitch|yaw|pitch-yaw] "
                 "[--motion M] [--strength S] [--params v1,...,v7] [--lag L]\n",
                 e.what());
    return 2;
  }
  if (!(seconds > kSettle)) {
    std::fprintf(stderr, "bench_gait: --seconds must exceed %g\n", kSettle);
    return 2;
  }
  std::vector<Row> rows;
  if (own) {
    rows.push_back(Measure(*own, seconds, 0.01, custom));
  }
  for (const Gait& g : mrsim::GaitPresets()) {
    if (own) break;
    if (!only.empty() &&
        std::find(only.begin(), only.end(), g.name) == only.end()) {
      continue;
    }
    std::fprintf(stderr, "bench_gait: %s ...\n", g.name.c_str());
    rows.push_back(Measure(g, seconds, 0.01));
  }
  // The motion commands (no BENCH lines: the table is for comparison).
  std::vector<Row> motions;
  if (!own && only.empty()) {
    struct M {
      const char* label;
      const char* preset;
      mrsim::Motion motion;
      double strength;
    };
    const M list[] = {
        {"turn-left 0.375", "forward", mrsim::Motion::kTurnLeft, 0.375},
        {"turn-left 1", "forward", mrsim::Motion::kTurnLeft, 1.0},
        {"turn-right 1", "forward", mrsim::Motion::kTurnRight, 1.0},
        {"backward", "forward", mrsim::Motion::kBackward, 1.0},
        {"sidewind-right", "sidewind", mrsim::Motion::kSidewindRight, 1.0},
    };
    for (const M& m : list) {
      std::fprintf(stderr, "bench_gait: %s ...\n", m.label);
      Custom c;
      c.motion = m.motion;
      c.strength = m.strength;
      if (m.motion == mrsim::Motion::kBackward) c.chain = "pitch";
      Row r = Measure(*mrsim::FindGaitPreset(m.preset), seconds, 0.01, c);
      r.preset = m.label;
      motions.push_back(r);
    }
  }
  std::printf(
      "11-module snake, flat ground, %.0f s (speed from t = %.0f s; heading "
      "and roll over the whole run)\n",
      seconds, kSettle);
  std::printf("%-15s %-10s %8s %8s %10s %12s %10s %7s\n", "preset", "chain",
              "dx(m)", "dy(m)", "speed", "heading", "roll", "wall");
  for (const Row& r : rows) {
    std::printf(
        "%-15s %-10s %8.3f %8.3f %6.4f bl/s %8.1f deg %6.0f deg %5.2fs\n",
        r.preset.c_str(), r.chain.c_str(), r.outcome.displacement.x(),
        r.outcome.displacement.y(), r.outcome.speed, r.outcome.heading_deg,
        r.outcome.roll_deg, r.wall_s);
  }
  if (!motions.empty()) {
    std::printf("motion commands (on the forward or sidewind preset):\n");
    for (const Row& r : motions) {
      std::printf(
          "%-15s %-10s %8.3f %8.3f %6.4f bl/s %8.1f deg %6.0f deg %5.2fs\n",
          r.preset.c_str(), r.chain.c_str(), r.outcome.displacement.x(),
          r.outcome.displacement.y(), r.outcome.speed, r.outcome.heading_deg,
          r.outcome.roll_deg, r.wall_s);
    }
  }
  for (const Row& r : rows) {
    std::string name = r.preset;
    std::replace(name.begin(), name.end(), '-', '_');
    std::printf("BENCH gait_speed_%s %.4f bl/s\n", name.c_str(),
                r.outcome.speed);
    std::printf("BENCH gait_heading_%s %.1f deg\n", name.c_str(),
                r.outcome.heading_deg);
  }
  return 0;
}

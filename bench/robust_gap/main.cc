// BENCH robust_gap: does training with robust fitness (--robust K, the mean
// over K perturbed worlds) give gaits that keep more of their fitness in a
// world that is not the model? Each trial (robust_gap_trial.h) trains
// CMA-ES twice with the same seed and budget, nominal and robust, and
// replays both bests in 50 perturbed worlds no training saw. Trials run
// over seeds 1-3 and two problems, one where the nominal optimum is a known
// exploit; the figure is the mean over trials of the robust gait's kept
// share over the nominal gait's (a share below 0.05 counts as 0.05, so one
// gait that keeps nothing cannot make the mean infinite).
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "bench/robust_gap/robust_gap_trial.h"

namespace {

constexpr double kEpisode = 5.0;  // s: short enough for 6 trials in minutes
constexpr uint64_t kSeeds[] = {1, 2, 3};
constexpr double kShareFloor = 0.05;

std::string Genes(const mrsim::Genome& g) {
  std::string s;
  for (double v : g) s += fmt::format(" {:.3f}", v);
  return s;
}

}  // namespace

int main() {
  const mrsim::RobustGapBudget budget;
  double ratio_sum = 0, nominal_sum = 0, robust_sum = 0, distance_sum = 0;
  int trials = 0;
  for (const mrsim::RobustGapTask& task :
       mrsim::RobustGapTasks(MRSIM_SOURCE_DIR, kEpisode)) {
    fmt::print("# {}: {}\n", task.name, task.why);
    for (uint64_t seed : kSeeds) {
      const mrsim::RobustGapResult r =
          mrsim::RunRobustGapTrial(task, seed, budget);
      for (const auto& [label, k] :
           {std::pair{"nominal", r.nominal_gait}, {"robust", r.robust_gait}}) {
        fmt::print(
            "{} seed {} {:<7} gait:{}  reported {:.3f} m, nominal {:.3f} m, "
            "mean of {} perturbed worlds {:.3f} m (keeps {:.2f})\n",
            task.name, seed, label, Genes(k.genes), k.reported, k.nominal,
            budget.replay_worlds, k.perturbed, k.share);
      }
      const double ratio = std::max(r.robust_gait.share, kShareFloor) /
                           std::max(r.nominal_gait.share, kShareFloor);
      // What a user sees in the other worlds: how far each gait goes.
      const double distance =
          r.nominal_gait.perturbed > 0
              ? r.robust_gait.perturbed / r.nominal_gait.perturbed
              : 0.0;
      fmt::print(
          "{} seed {}: robust keeps {:.2f}, nominal {:.2f}: {:.2f} x; in the "
          "perturbed worlds the robust gait goes {:.2f} x as far\n",
          task.name, seed, r.robust_gait.share, r.nominal_gait.share, ratio,
          distance);
      distance_sum += distance;
      std::fflush(stdout);
      ratio_sum += ratio;
      nominal_sum += r.nominal_gait.share;
      robust_sum += r.robust_gait.share;
      ++trials;
    }
  }
  fmt::print("BENCH robust_gap_nominal_share {:.2f} share\n",
             nominal_sum / trials);
  fmt::print("BENCH robust_gap_robust_share {:.2f} share\n",
             robust_sum / trials);
  fmt::print("BENCH robust_gap_distance_ratio {:.2f} x\n",
             distance_sum / trials);
  fmt::print("BENCH robust_gap {:.2f} x\n", ratio_sum / trials);
  return 0;
}

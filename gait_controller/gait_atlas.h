// The gait atlas: every gait preset, the motion commands and the minimal
// configurations of published work, each run on its robot and recorded in
// docs/gait_atlas.csv with the spread over small amplitude changes and a
// tolerance, so a physics change that moves what a gait does is noticed
// (docs/physics.md, "Gait atlas").
#pragma once

#include <array>
#include <string>
#include <vector>

#include "gait_controller/atlas_table.h"
#include "gait_controller/gait.h"
#include "gait_controller/gait_trial.h"

namespace mrsim {

// One line of the atlas: a gait, the run that measures it and where the
// expectation comes from.
struct AtlasEntry {
  std::string name;    // the line's name in the table
  std::string source;  // "preset", "motion", "task" or a citation
  std::string robot;   // the table's robot column; "": from the trial
  Gait gait;
  GaitTrial trial;
};

// The amplitude factors a chaotic line is checked with: the mean of its
// runs with every amplitude of the gait times 0.998, 0.999, 1, 1.001 and
// 1.002. A chaotic gait (lateral undulation) moves by several per cent
// between them; a regular one not measurably.
inline constexpr std::array<double, 5> kAtlasFactors = {0.998, 0.999, 1.0,
                                                        1.001, 1.002};
// The factors the spread is measured over when the table is made: those
// five and eight more between them, since the spread of five runs is
// itself too uncertain to set a tolerance by (docs/physics.md).
inline constexpr std::array<double, 13> kAtlasSpreadFactors = {
    0.998,  0.9983, 0.9986, 0.999,  0.9993, 0.9996, 1.0,
    1.0004, 1.0007, 1.001,  1.0014, 1.0017, 1.002};

// How tolerances follow from the measured spread (docs/physics.md):
// tolerance = max(k * spread * sqrt(2 / samples), relative * |value| +
// floor), sqrt(2 / samples) because the check compares two measurements of
// `samples` runs each.
struct AtlasTolerancePolicy {
  double k = 4.0;
  double relative = 0.02;
  // speed, drift and rise bl/s, heading and roll deg (AtlasQuantity order)
  std::array<double, kAtlasQuantities> floor = {0.0003, 0.0003, 0.0003, 0.3,
                                                1.0};
};

// Every line, in table order: the presets (bench_gait's robots), the
// motion commands, then the published configurations.
const std::vector<AtlasEntry>& AtlasEntries();
// The entry of `entries` named `name`. Throws AtlasTableError when there
// is none.
const AtlasEntry& FindAtlasEntry(
    const std::string& name,
    const std::vector<AtlasEntry>& entries = AtlasEntries());

// `gait` with every amplitude (both groups and the overrides) times
// `factor`.
Gait ScaleAmplitudes(Gait gait, double factor);

// The quantities of one run in AtlasQuantity order.
std::array<double, kAtlasQuantities> AtlasQuantities(const GaitOutcome& run);

// What the check compares with a line: with samples 1 the run at nominal
// amplitude, otherwise the mean over kAtlasFactors. `scale` multiplies the
// amplitudes first (1: the entry as it is). Throws std::invalid_argument
// for samples other than 1 or kAtlasFactors.size().
std::array<double, kAtlasQuantities> MeasureAtlasValues(const AtlasEntry& entry,
                                                        int samples,
                                                        double scale = 1.0);

// The table line of `entry` from its runs at every factor of
// kAtlasSpreadFactors (in that order): the spread of each quantity over
// them, and samples 1 unless the spread, not the floor, would set a single
// run's tolerance (then the line is checked by its mean over the runs at
// kAtlasFactors). Throws std::invalid_argument for another number of runs.
AtlasLine MakeAtlasLine(const AtlasEntry& entry,
                        const std::vector<GaitOutcome>& runs,
                        const AtlasTolerancePolicy& policy = {});

// Runs the entry at every factor of kAtlasSpreadFactors and makes its line
// (what gait_atlas --write does for each entry).
AtlasLine MeasureAtlasLine(const AtlasEntry& entry,
                           const AtlasTolerancePolicy& policy = {});

}  // namespace mrsim

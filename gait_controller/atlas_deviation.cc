#include "gait_controller/atlas_deviation.h"

#include <fmt/format.h>

#include <cmath>

namespace mrsim {

std::vector<AtlasDeviation> CompareAtlasLine(
    const AtlasLine& expected,
    const std::array<double, kAtlasQuantities>& measured) {
  std::vector<AtlasDeviation> out;
  for (int i = 0; i < kAtlasQuantities; ++i) {
    AtlasDeviation d;
    d.line = expected.name;
    d.quantity = static_cast<AtlasQuantity>(i);
    d.expected = expected.values[i].value;
    d.measured = measured[i];
    d.tolerance = expected.values[i].tolerance;
    // NaN (a run that went wrong) is beyond any tolerance.
    d.beyond = !(std::abs(d.measured - d.expected) <= d.tolerance);
    out.push_back(d);
  }
  return out;
}

bool AnyBeyond(const std::vector<AtlasDeviation>& deviations) {
  for (const AtlasDeviation& d : deviations) {
    if (d.beyond) return true;
  }
  return false;
}

std::string DescribeAtlasDeviations(
    const std::vector<AtlasDeviation>& deviations) {
  std::string text;
  for (const AtlasDeviation& d : deviations) {
    if (!d.beyond) continue;
    const double change = d.measured - d.expected;
    const std::string percent =
        d.expected != 0
            ? fmt::format(", {:+.1f} %", 100.0 * change / std::abs(d.expected))
            : "";
    text += fmt::format(
        "gait atlas line '{}' moved: {} {:.6g} -> {:.6g} {} ({:+.6g}{}; "
        "tolerance {:.6g})\n",
        d.line, AtlasQuantityName(d.quantity), d.expected, d.measured,
        AtlasQuantityUnit(d.quantity), change, percent, d.tolerance);
  }
  if (!text.empty()) {
    text +=
        "If the change is meant (a physics or gait change), regenerate the "
        "table with\n  build/bench/gait/gait_atlas --write "
        "docs/gait_atlas.csv\nand add a line to docs/physics.md (\"Gait "
        "atlas\") saying what moved and why.\n";
  }
  return text;
}

}  // namespace mrsim

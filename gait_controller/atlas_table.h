// The gait atlas as a table (docs/gait_atlas.csv): for each line (a gait
// on a robot), what it does (speed, drift, rise, heading change, roll) with
// the
// spread over small amplitude changes and the tolerance a later build must
// stay within. Written by gait_atlas --write, read by the atlas tests.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrsim {

// The quantities of a line, in table order (GaitOutcome says what each is).
enum class AtlasQuantity { kSpeed, kDrift, kRise, kHeading, kRoll };
inline constexpr int kAtlasQuantities = 5;

// "speed", "drift", "rise", "heading", "roll".
const char* AtlasQuantityName(AtlasQuantity q);
// "bl/s" for speed, drift and rise, "deg" for heading and roll.
const char* AtlasQuantityUnit(AtlasQuantity q);

struct AtlasValue {
  double value = 0.0;      // the run at nominal amplitude, or the mean
  double spread = 0.0;     // standard deviation over the perturbed runs
  double tolerance = 0.0;  // how far a later measurement may be from value
};

struct AtlasLine {
  std::string name;   // unique: the preset, motion or configuration
  std::string robot;  // "pitch x11", "pitch-yaw x11 wheels", ...
  // 1: value is the nominal run; more: the mean over that many runs with
  // the amplitudes scaled by kAtlasFactors (a chaotic line).
  int samples = 1;
  std::array<AtlasValue, kAtlasQuantities> values;

  const AtlasValue& at(AtlasQuantity q) const {
    return values[static_cast<int>(q)];
  }
  AtlasValue& at(AtlasQuantity q) { return values[static_cast<int>(q)]; }
};

// A table that cannot be read: what() names the line and the field.
class AtlasTableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The CSV text: '#' comment lines saying how to regenerate it, a header,
// then one row per line with 6 significant digits.
std::string FormatAtlasTable(const std::vector<AtlasLine>& lines);
// Parses FormatAtlasTable's text (comments and blank lines skipped).
// `origin` names the text in errors. Throws AtlasTableError.
std::vector<AtlasLine> ParseAtlasTable(const std::string& text,
                                       const std::string& origin);
// Reads and parses a file. Throws AtlasTableError (also when unreadable).
std::vector<AtlasLine> ReadAtlasTable(const std::string& path);
// The line named `name`. Throws AtlasTableError when there is none.
const AtlasLine& FindAtlasLine(const std::vector<AtlasLine>& lines,
                               const std::string& name);

}  // namespace mrsim

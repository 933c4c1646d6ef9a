// Numbers in checkpoints and state files: written so they read back bit
// for bit, and read only when the whole text is a number. One writer and
// one reader for every file mrsim resumes from.
#pragma once

#include <optional>
#include <string>

namespace mrsim {

// C99 hexadecimal floating point ("0x1.8p+1"): exact, unlike %g.
std::string ExactNumber(double value);

// The whole of `text` as a number (decimal or hexadecimal, inf and nan
// too); nothing when it is empty or anything else follows the number.
std::optional<double> ParseWholeNumber(const std::string& text);

}  // namespace mrsim

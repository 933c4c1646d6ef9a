// How far apart two words are, for "did you mean" in messages about a
// mistyped option, tool or name.
#pragma once

#include <cstddef>
#include <string>

namespace mrsim {

// Levenshtein distance: single-character inserts, deletes and changes.
std::size_t EditDistance(const std::string& a, const std::string& b);

}  // namespace mrsim

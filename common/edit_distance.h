// How far apart two words are, for "did you mean" in messages about a
// mistyped option, subcommand, tool or name.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace mrsim {

// Levenshtein distance: single-character inserts, deletes and changes.
std::size_t EditDistance(const std::string& a, const std::string& b);

// Jaro-Winkler similarity in [0, 1] (1: equal). Unlike the edit distance
// it weighs a shared beginning, where typos are rare: "gate" is nearer
// "gait" than "rate" (one change away), as a user who typed it meant.
double WordSimilarity(const std::string& a, const std::string& b);

// The candidate a user most probably meant by `typed` ("--gate" ->
// "--gait", "pase" -> "pause"), or "" when none is similar enough. Leading
// dashes are ignored when comparing, so "-gait" finds "--gait".
std::string NearestWord(const std::string& typed,
                        const std::vector<std::string>& candidates);

}  // namespace mrsim

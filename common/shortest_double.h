// The shortest text that reads back to the same double, fast (Dragonbox
// with its full table): what the CSV logger and the JSON of MCAP files
// write numbers with, so a number reads the same in both and loses nothing.
// The layout is std::to_chars's (fixed or scientific, whichever is
// shorter; "0.1", "1e-05", "inf", "nan").
#pragma once

namespace mrsim {

// Writes v at p (at most kMaxDoubleChars characters); returns the end.
inline constexpr int kMaxDoubleChars = 32;
char* WriteDouble(double v, char* p);

}  // namespace mrsim

// Waiting in tests: check a condition until it holds or a deadline passes.
// Tests wait through these, which sleep only between two checks, never
// instead of one: a result never depends on how long something took.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace mrsim::testing {

// Checks `done` every poll_s until it holds (true) or timeout_s has passed
// (false, after one last check).
bool WaitUntil(const std::function<bool()>& done, double timeout_s,
               double poll_s = 0.02);

// Runs `step`, then checks `done`, every period_s until done holds (true)
// or timeout_s has passed (false). For a publisher that repeats its message
// until the effect is seen, or a stand-in source with a steady rate.
bool RepeatUntil(const std::function<void()>& step,
                 const std::function<bool()>& done, double period_s,
                 double timeout_s);

// The whole file ("" when it cannot be read).
std::string ReadFileText(const std::string& path);
// Lines ('\n') in the file (0 when it cannot be read).
size_t CountLines(const std::string& path);
// Waits until the file holds `text`.
bool WaitForFileText(const std::string& path, const std::string& text,
                     double timeout_s);
// Waits until the file has at least `lines` whole lines.
bool WaitForLines(const std::string& path, size_t lines, double timeout_s);

}  // namespace mrsim::testing

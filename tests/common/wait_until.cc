#include "tests/common/wait_until.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

namespace mrsim::testing {

namespace {

using Clock = std::chrono::steady_clock;

Clock::time_point After(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(
                            std::chrono::duration<double>(seconds));
}

}  // namespace

bool WaitUntil(const std::function<bool()>& done, double timeout_s,
               double poll_s) {
  return RepeatUntil([] {}, done, poll_s, timeout_s);
}

bool RepeatUntil(const std::function<void()>& step,
                 const std::function<bool()>& done, double period_s,
                 double timeout_s) {
  const Clock::time_point end = After(timeout_s);
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(period_s));
  Clock::time_point next = Clock::now();
  while (true) {
    step();
    if (done()) return true;
    if (Clock::now() >= end) return false;
    next = std::max(next + period, Clock::now());
    // Between two checks only: the deadline and `done` decide.
    std::this_thread::sleep_until(std::min(next, end));
  }
}

std::string ReadFileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

size_t CountLines(const std::string& path) {
  const std::string text = ReadFileText(path);
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

bool WaitForFileText(const std::string& path, const std::string& text,
                     double timeout_s) {
  return WaitUntil(
      [&] { return ReadFileText(path).find(text) != std::string::npos; },
      timeout_s);
}

bool WaitForLines(const std::string& path, size_t lines, double timeout_s) {
  return WaitUntil([&] { return CountLines(path) >= lines; }, timeout_s);
}

}  // namespace mrsim::testing

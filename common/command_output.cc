#include "common/command_output.h"

#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "common/subprocess.h"

namespace mrsim {

std::string FindOnPath(const std::string& program) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (program.find('/') != std::string::npos) {
    return fs::exists(program, ec) ? program : "";
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    std::size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    const std::string dir = dirs.substr(start, end - start);
    if (!dir.empty()) {
      const fs::path candidate = fs::path(dir) / program;
      if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    start = end + 1;
  }
  return "";
}

CommandOutput RunForOutput(const std::vector<std::string>& argv,
                           double timeout_s) {
  if (argv.empty()) throw std::invalid_argument("RunForOutput: empty argv");
  std::vector<std::string> args = argv;
  const std::string path = FindOnPath(args[0]);
  if (path.empty()) {
    throw std::runtime_error("cannot start " + args[0] + ": not found on PATH");
  }
  args[0] = path;
  SpawnOptions options;
  options.output = SpawnOptions::Output::kPipe;
  Subprocess child(args, options);
  CommandOutput result;
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  char buffer[4096];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - Clock::now())
                          .count();
    if (left <= 0) {
      result.timed_out = true;
      break;
    }
    pollfd fd{child.output_fd(), POLLIN, 0};
    const int ready = poll(&fd, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = read(child.output_fd(), buffer, sizeof buffer);
    if (n > 0) {
      const std::size_t room = CommandOutput::kMaxOutput - result.output.size();
      result.output.append(buffer, std::min(room, static_cast<std::size_t>(n)));
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
    break;  // end of output: the program closed it (it is ending)
  }
  if (result.timed_out) {
    result.exit_code = child.Stop(1.0);
    return result;
  }
  const auto left =
      std::chrono::duration<double>(deadline - Clock::now()).count();
  result.exit_code = child.Wait(std::max(0.1, left));
  if (result.exit_code < 0) {
    result.timed_out = true;
    result.exit_code = child.Stop(1.0);
  }
  return result;
}

}  // namespace mrsim

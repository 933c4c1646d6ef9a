#include "launcher/process_group.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <utility>

namespace mrsim {
namespace {

constexpr int kColours[] = {36, 33, 32, 35, 34, 31};

bool IsStopSignal(int sig) { return sig == SIGINT || sig == SIGTERM; }

// Ended by a stop signal, or exited 128 + one (as a JVM, or mrsim-opt
// leaving a run unfinished, do).
bool EndedByStopSignal(int status) {
  return (WIFSIGNALED(status) && IsStopSignal(WTERMSIG(status))) ||
         (WIFEXITED(status) && IsStopSignal(WEXITSTATUS(status) - 128));
}

// A process the group stopped, that ended as asked, just "stopped": not
// "exited with code 130", which reads as a failure.
std::string DescribeStatus(int status, bool stopped_by_us) {
  if (stopped_by_us && EndedByStopSignal(status)) return "stopped";
  return DescribeExitStatus(status);
}

}  // namespace

ProcessGroup::ProcessGroup(std::FILE* out)
    : out_(out), colour_(isatty(fileno(out)) != 0) {}

ProcessGroup::ProcessGroup(LineSink sink) : sink_(std::move(sink)) {}

ProcessGroup::~ProcessGroup() { StopAll(2.0); }

void ProcessGroup::Start(const ProcessSpec& spec,
                         const std::string& program_path) {
  std::vector<std::string> argv{program_path};
  argv.insert(argv.end(), spec.args.begin(), spec.args.end());
  SpawnOptions options;
  options.output = SpawnOptions::Output::kPipe;
  options.own_process_group = spec.stop_last;
  Child child;
  try {
    child.process = std::make_unique<Subprocess>(argv, options);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot start " + spec.name + " (" + program_path +
                             "): " + e.what());
  }
  child.spec = spec;
  if (!spec.ready_line.empty()) {
    child.ready_line = std::make_shared<const std::regex>(spec.ready_line);
  }
  child.running = true;
  child.colour = kColours[children_.size() % std::size(kColours)];
  name_width_ = std::max(name_width_, spec.name.size());
  const pid_t pid = child.process->pid();
  children_.push_back(std::move(child));
  Say("started " + spec.name + " (pid " + std::to_string(pid) +
      "): " + program_path);
}

void ProcessGroup::PrintLine(Child& child, const std::string& line) {
  if (child.ready_line && std::regex_search(line, *child.ready_line)) {
    child.ready_line.reset();
  }
  if (sink_) {
    sink_(child.spec.name, line);
    return;
  }
  if (colour_) {
    std::fprintf(out_, "\033[%dm[%-*s]\033[0m %s\n", child.colour,
                 static_cast<int>(name_width_), child.spec.name.c_str(),
                 line.c_str());
  } else {
    std::fprintf(out_, "[%-*s] %s\n", static_cast<int>(name_width_),
                 child.spec.name.c_str(), line.c_str());
  }
  std::fflush(out_);
}

void ProcessGroup::Say(const std::string& line) {
  if (sink_) {
    sink_("launch", line);
    return;
  }
  std::fprintf(out_, "[%-*s] %s\n", static_cast<int>(name_width_), "launch",
               line.c_str());
  std::fflush(out_);
}

void ProcessGroup::Forward(Child& child, bool flush_partial) {
  const int fd = child.process ? child.process->output_fd() : -1;
  if (fd < 0) return;
  // The pipe is non-blocking: read what is there and go back to polling, so
  // one quiet child never delays noticing that another one exited.
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof(buffer));
    if (n > 0) {
      child.pending.append(buffer, static_cast<size_t>(n));
      size_t start = 0;
      for (size_t nl;
           (nl = child.pending.find('\n', start)) != std::string::npos;
           start = nl + 1) {
        PrintLine(child, child.pending.substr(start, nl - start));
      }
      child.pending.erase(0, start);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n == 0 || errno != EAGAIN) {
      // End of output: the process closed its side.
      if (!child.pending.empty()) PrintLine(child, child.pending);
      child.pending.clear();
      child.process->CloseOutput();
    }
    break;
  }
  if (flush_partial && !child.pending.empty()) {
    PrintLine(child, child.pending);
    child.pending.clear();
  }
}

void ProcessGroup::Reap(Child& child, int status) {
  child.running = false;
  child.status = status;
  Forward(child, true);
  Say(child.spec.name + " " + DescribeStatus(status, child.stopped_by_us));
}

std::string ProcessGroup::Poll(int timeout_ms) {
  std::vector<pollfd> fds;
  std::vector<Child*> owners;
  for (auto& c : children_) {
    if (c.process->output_fd() >= 0) {
      fds.push_back({c.process->output_fd(), POLLIN, 0});
      owners.push_back(&c);
    }
  }
  if (fds.empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
  } else if (poll(fds.data(), fds.size(), timeout_ms) > 0) {
    for (size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].revents != 0) Forward(*owners[i], false);
    }
  }
  std::string ended_required;
  for (auto& c : children_) {
    if (!c.running) continue;
    if (!c.process->running()) {
      Reap(c, c.process->status());
      if (c.spec.required && ended_required.empty()) {
        ended_required = c.spec.name;
      }
    }
  }
  return ended_required;
}

void ProcessGroup::StopAll(double grace_s) {
  // Clients first, in reverse start order (consumers before the
  // simulator), then the hubs they talk through.
  StopStage([](const ProcessSpec& s) { return !s.stop_last; }, grace_s);
  StopStage([](const ProcessSpec& s) { return s.stop_last; }, grace_s);
  for (auto& c : children_) {
    Forward(c, true);
  }
}

void ProcessGroup::Stop(const Which& which, double grace_s) {
  StopStage(which, grace_s);
}

void ProcessGroup::StopStage(const Which& which, double grace_s) {
  using Clock = std::chrono::steady_clock;
  const auto stage_running = [&] { return AnyRunning(which); };
  const int signals[] = {SIGINT, SIGTERM, SIGKILL};
  for (int sig : signals) {
    bool any = false;
    for (auto it = children_.rbegin(); it != children_.rend(); ++it) {
      if (it->running && which(it->spec)) {
        it->stopped_by_us = true;
        it->process->Signal(sig);
        any = true;
      }
    }
    if (!any) break;
    const auto deadline = Clock::now() + std::chrono::duration<double>(
                                             sig == SIGKILL ? 5.0 : grace_s);
    while (stage_running() && Clock::now() < deadline) Poll(50);
    if (!stage_running()) break;
    Say(std::string("some processes ignored ") + strsignal(sig) +
        ", escalating");
  }
}

bool ProcessGroup::IsReady(const std::string& name) const {
  return std::any_of(children_.begin(), children_.end(), [&](const Child& c) {
    return c.spec.name == name && !c.ready_line;
  });
}

bool ProcessGroup::AnyRunning() const {
  return std::any_of(children_.begin(), children_.end(),
                     [](const Child& c) { return c.running; });
}

bool ProcessGroup::AnyRunning(const Which& which) const {
  return std::any_of(children_.begin(), children_.end(), [&](const Child& c) {
    return c.running && which(c.spec);
  });
}

bool ProcessGroup::AllClean(bool interrupted) const {
  for (const auto& c : children_) {
    if (c.running) return false;
    if (WIFEXITED(c.status) && WEXITSTATUS(c.status) == 0) continue;
    const bool stopped = EndedByStopSignal(c.status);
    if (!stopped || !(c.stopped_by_us || interrupted)) return false;
  }
  return true;
}

std::string ProcessGroup::Summary() const {
  std::string s;
  for (const auto& c : children_) {
    s += "  " + c.spec.name + ": " +
         (c.running ? std::string("running")
                    : DescribeStatus(c.status, c.stopped_by_us)) +
         "\n";
  }
  return s;
}

}  // namespace mrsim

#include "launcher/launch_command.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "common/data_dir.h"
#include "common/edit_distance.h"
#include "launcher/process_group.h"
#include "launcher/program_locator.h"
#include "launcher/shell_quote.h"

namespace mrsim {

const char* FrontDoorHelp() {
  return "mrsim: modular robot simulator front door.\n"
         "  mrsim launch FILE    start the processes of a launch file\n"
         "  mrsim run FILE       run a design headless with its saved "
         "controller\n"
         "  mrsim keygen PATH    write a key for signed messages\n"
         "  mrsim TOOL ARGS...   run mrsim-TOOL: scenario, studio, sim, "
         "gait, ctl, log, plot, view, opt, worker, lcm-spy, summary, run";
}

void AddLaunchFlags(CLI::App& launch, LaunchCommand& c) {
  launch.add_option("file", c.file, "Launch file (XML)")->required();
  launch.add_option("--set", c.sets, "Override an <arg>: NAME=VALUE");
  launch.add_option("--without", c.without, "Leave a process out (by name)");
  launch.add_option("--key-file", c.key_file,
                    "Sign every process's messages with this key (passed "
                    "on as MRSIM_KEY_FILE; docs/security.md)");
  launch.add_flag("--dry-run", c.dry_run,
                  "Print the resolved commands and start nothing");
}

std::string FindLaunchFile(const std::string& file) {
  std::error_code ec;
  if (file.find('/') != std::string::npos ||
      std::filesystem::exists(file, ec)) {
    return file;
  }
  const std::string bundled = FindDataFile("launch/" + file);
  return bundled.empty() ? file : bundled;
}

LaunchPlan PlanLaunch(const std::string& argv0, const LaunchCommand& c) {
  std::map<std::string, std::string> overrides;
  for (const auto& s : c.sets) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw LaunchError("--set " + s + ": expected NAME=VALUE");
    }
    overrides[s.substr(0, eq)] = s.substr(eq + 1);
  }
  LaunchFile launch = ReadLaunchFile(FindLaunchFile(c.file), overrides);
  for (const auto& name : c.without) {
    bool found = false;
    for (auto& p : launch.processes) {
      if (p.name == name) {
        p.enabled = false;
        found = true;
      }
    }
    if (!found) {
      throw LaunchError(c.file + ": --without " + name +
                        ": no process of that name");
    }
  }
  const auto search = ProgramSearchPath(argv0);
  LaunchPlan plan;
  plan.name = launch.name;
  for (const auto& p : launch.processes) {
    if (!p.enabled) continue;
    try {
      plan.processes.emplace_back(p, FindProgram(p.program, search));
    } catch (const std::runtime_error& e) {
      // A typo in the file: bad input, named where it is.
      throw LaunchError(c.file + ":" + std::to_string(p.line) + ": process '" +
                        p.name + "': " + e.what());
    }
  }
  if (plan.processes.empty()) {
    throw LaunchError(c.file + ": every process is left out");
  }
  return plan;
}

namespace {

// A JVM starting the hub on a busy 2-core machine takes a few seconds.
constexpr std::chrono::seconds kReadyPortTimeout{30};

bool TcpPortAccepts(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool ok = connect(fd, reinterpret_cast<const sockaddr*>(&address),
                          sizeof(address)) == 0;
  close(fd);
  return ok;
}

// Waits until `spec`'s process prints its ready line. Returns "" when it
// did or a stop was asked; else why the launch ends: a required process
// ended meanwhile, or this one ended or stayed silent past the deadline.
// `not_ready` is set in the last two cases: the launch failed.
std::string WaitUntilReady(const ProcessSpec& spec,
                           const std::function<bool()>& stop,
                           ProcessGroup& group, bool& not_ready) {
  const auto deadline = std::chrono::steady_clock::now() + kReadyPortTimeout;
  const auto this_one = [&](const ProcessSpec& s) {
    return s.name == spec.name;
  };
  while (!stop() && !group.IsReady(spec.name)) {
    const std::string ended = group.Poll(20);
    if (!ended.empty()) return ended;
    if (group.IsReady(spec.name)) break;
    if (!group.AnyRunning(this_one)) {
      not_ready = true;
      return fmt::format("{} (ended before printing a line matching '{}')",
                         spec.name, spec.ready_line);
    }
    if (std::chrono::steady_clock::now() > deadline) {
      not_ready = true;
      return fmt::format("{} (no line matching '{}' after {} s)", spec.name,
                         spec.ready_line, kReadyPortTimeout.count());
    }
  }
  return "";
}

// After a required process ended: the processes that may finish their
// work (ProcessSpec::finish_s) are given that long to end by themselves,
// the others are stopped now. A stop request cuts the wait short.
void LetFinish(const LaunchPlan& plan, const std::string& ended,
               const std::function<bool()>& stop, ProcessGroup& group) {
  const auto finishing = [](const ProcessSpec& s) { return s.finish_s > 0; };
  if (!group.AnyRunning(finishing)) {
    group.Say(ended + " ended, stopping the others");
    return;
  }
  std::string names;
  for (const auto& [spec, path] : plan.processes) {
    const std::string& name = spec.name;
    if (spec.finish_s > 0 && group.AnyRunning([&](const ProcessSpec& s) {
          return s.name == name;
        })) {
      names += fmt::format("{}{} (up to {:g} s)", names.empty() ? "" : ", ",
                           name, spec.finish_s);
    }
  }
  group.Say(ended + " ended; letting " + names +
            " finish, stopping the others (Ctrl-C stops all now)");
  group.Stop(
      [](const ProcessSpec& s) { return s.finish_s <= 0 && !s.stop_last; },
      10.0);
  const auto start = std::chrono::steady_clock::now();
  while (!stop()) {
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    for (const auto& [spec, path] : plan.processes) {
      const std::string& name = spec.name;
      const auto this_one = [&](const ProcessSpec& s) {
        return s.name == name;
      };
      if (spec.finish_s > 0 && waited >= spec.finish_s &&
          group.AnyRunning(this_one)) {
        group.Say(fmt::format("{} has not finished after {:g} s, stopping it",
                              name, spec.finish_s));
        group.Stop(this_one, 10.0);
      }
    }
    if (!group.AnyRunning(finishing)) break;
    group.Poll(100);
  }
}

}  // namespace

void PrintPlan(const LaunchPlan& plan, std::ostream& out) {
  for (const auto& [spec, path] : plan.processes) {
    out << spec.name << (spec.required ? " (required)" : "") << ": " << path;
    for (const auto& a : spec.args) out << " " << ShellQuote(a);
    out << "\n";
  }
}

int RunLaunch(const LaunchPlan& plan, const std::function<bool()>& stop,
              std::FILE* out) {
  ProcessGroup group(out);
  for (const auto& [spec, path] : plan.processes) group.FitName(spec.name);
  group.Say("launch " + plan.name + ": " +
            std::to_string(plan.processes.size()) +
            " processes; Ctrl-C stops them all");
  std::string ended;
  bool not_ready = false;  // a process the others wait for never got ready
  for (const auto& [spec, path] : plan.processes) {
    const auto start = std::chrono::steady_clock::now();
    while (spec.delay_s > 0 && !stop() && ended.empty() &&
           std::chrono::steady_clock::now() - start <
               std::chrono::duration<double>(spec.delay_s)) {
      ended = group.Poll(20);
    }
    if (stop() || !ended.empty()) break;
    group.Start(spec, path);
    if (spec.ready_port > 0) {
      const auto deadline =
          std::chrono::steady_clock::now() + kReadyPortTimeout;
      while (!stop() && ended.empty() && !TcpPortAccepts(spec.ready_port)) {
        if (std::chrono::steady_clock::now() > deadline) {
          not_ready = true;
          ended = fmt::format(
              "{} (not accepting connections on port {} after "
              "{} s)",
              spec.name, spec.ready_port, kReadyPortTimeout.count());
          break;
        }
        ended = group.Poll(50);
      }
    }
    if (!spec.ready_line.empty()) {
      ended = WaitUntilReady(spec, stop, group, not_ready);
      if (!ended.empty()) break;
    }
  }
  while (ended.empty() && !stop() && group.AnyRunning()) {
    ended = group.Poll(100);
  }
  if (stop()) {
    group.Say("stop requested, stopping every process");
  } else if (!ended.empty()) {
    LetFinish(plan, ended, stop, group);
  }
  group.StopAll(10.0);
  group.Say("all stopped:\n" + group.Summary());
  // A terminal's Ctrl-C reaches the children too, and one may end before
  // StopAll signals it.
  return group.AllClean(stop()) && !not_ready ? 0 : 1;
}

void ExecTool(const std::string& argv0, const std::string& tool,
              std::vector<std::string> args) {
  std::string path;
  try {
    path = FindProgram("mrsim-" + tool, ProgramSearchPath(argv0));
  } catch (const std::runtime_error& e) {
    // A mistyped tool is bad input, like a mistyped flag; "lanch" is most
    // likely the subcommand.
    if (EditDistance(tool, "launch") <= 2) {
      throw LaunchError("no tool '" + tool +
                        "' (did you mean 'mrsim launch FILE'?)");
    }
    throw LaunchError("no tool '" + tool + "': " + e.what());
  }
  args.insert(args.begin(), path);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(path.c_str(), argv.data());
  throw std::runtime_error("cannot run " + path);
}

}  // namespace mrsim

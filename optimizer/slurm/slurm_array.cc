#include "optimizer/slurm/slurm_array.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <sstream>

namespace mrsim {
namespace {

std::string Trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

// The first line of a program's output, for an error message.
std::string FirstLine(const std::string& text) {
  const std::string t = Trim(text);
  const std::string line = t.substr(0, t.find('\n'));
  return line.size() > 300 ? line.substr(0, 300) + "..." : line;
}

bool AllDigits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
}

// How many tasks "3", "[4-7%2]" or "[1,3-5]" names.
int TaskCount(std::string spec) {
  if (spec.empty()) return 0;
  if (spec.front() != '[') return 1;
  spec =
      spec.substr(1, spec.find(']') == std::string::npos ? std::string::npos
                                                         : spec.find(']') - 1);
  spec = spec.substr(0, spec.find('%'));  // "%2": at most 2 at once
  int count = 0;
  std::stringstream parts(spec);
  std::string part;
  while (std::getline(parts, part, ',')) {
    const auto dash = part.find('-');
    if (dash == std::string::npos) {
      if (AllDigits(part)) ++count;
      continue;
    }
    const std::string a = part.substr(0, dash), b = part.substr(dash + 1);
    if (!AllDigits(a) || !AllDigits(b) || a.size() > 9 || b.size() > 9) {
      continue;
    }
    const long first = std::stol(a), last = std::stol(b);
    if (last >= first) count += static_cast<int>(last - first + 1);
  }
  return count;
}

}  // namespace

std::string NormaliseSbatchOption(const std::string& option) {
  const std::string o = Trim(option);
  if (o.empty()) throw SlurmError("--slurm-opt: empty sbatch option");
  const std::string full = o.front() == '-' ? o : "--" + o;
  const std::string name = full.substr(0, full.find('='));
  for (const char* own :
       {"--array", "--parsable", "--wrap", "--output", "-a", "-o"}) {
    if (name == own) {
      throw SlurmError(fmt::format(
          "--slurm-opt {}: mrsim-opt sets {} itself (the array is --slurm "
          "N; the workers' logs go to --out's slurm/ folder)",
          option, name));
    }
  }
  return full;
}

SlurmCounts ParseSqueue(const std::string& output) {
  SlurmCounts counts;
  counts.known = true;
  std::stringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    std::stringstream fields(line);
    std::string id, state;
    if (!(fields >> id >> state)) continue;
    const auto underscore = id.find('_');
    const int n = underscore == std::string::npos
                      ? 1
                      : TaskCount(id.substr(underscore + 1));
    if (state == "PENDING" || state == "REQUEUED" || state == "REQUEUE_FED" ||
        state == "REQUEUE_HOLD" || state == "RESV_DEL_HOLD") {
      counts.pending += n;
    } else if (state == "RUNNING" || state == "CONFIGURING") {
      counts.running += n;
    } else {
      counts.other += n;
    }
  }
  return counts;
}

SlurmArray::SlurmArray(SlurmRunner& runner, SlurmArraySettings settings)
    : runner_(runner), settings_(std::move(settings)) {
  if (settings_.tasks < 1) throw SlurmError("--slurm: expected N >= 1");
  for (std::string& o : settings_.options) o = NormaliseSbatchOption(o);
}

SlurmArray::~SlurmArray() {
  try {
    Cancel();
  } catch (...) {  // a destructor never throws; the job ends with its time
  }
}

std::vector<std::string> SlurmArray::SubmitCommand() const {
  std::vector<std::string> argv = {
      "sbatch", "--parsable", fmt::format("--array=0-{}", settings_.tasks - 1),
      "--job-name=" + settings_.job_name,
      // A task whose node fails or that is preempted comes back and
      // re-joins the farm (the master takes a new worker at any time).
      "--requeue"};
  if (!settings_.output.empty()) argv.push_back("--output=" + settings_.output);
  argv.insert(argv.end(), settings_.options.begin(), settings_.options.end());
  argv.push_back("--wrap=" + settings_.command);
  return argv;
}

void SlurmArray::Submit() {
  if (!job_id_.empty()) return;
  const CommandOutput out = runner_.Run(SubmitCommand());
  if (out.exit_code != 0) {
    throw SlurmError(fmt::format("sbatch failed ({}): {}",
                                 out.timed_out
                                     ? std::string("no answer in time")
                                     : fmt::format("exit {}", out.exit_code),
                                 FirstLine(out.output)));
  }
  // --parsable: "JOBID" or "JOBID;CLUSTER", after any warnings.
  std::string id;
  std::stringstream lines(out.output);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string candidate = Trim(line.substr(0, line.find(';')));
    if (AllDigits(candidate)) id = candidate;
  }
  if (id.empty()) {
    throw SlurmError("sbatch answered no job id: " + FirstLine(out.output));
  }
  job_id_ = id;
}

bool SlurmArray::Poll(double now) {
  if (job_id_.empty() || cancelled_) return false;
  if (polled_ && now - last_poll_ < settings_.poll_interval) return false;
  polled_ = true;
  last_poll_ = now;
  CommandOutput out;
  try {
    out = runner_.Run({"squeue", "--noheader", "--array", "--jobs=" + job_id_,
                       "--format=%i %T"});
  } catch (const std::exception& e) {
    last_error_ = e.what();
    return true;
  }
  // squeue says "Invalid job id" (exit 1) once the job has left its list.
  if (out.exit_code != 0 &&
      out.output.find("Invalid job id") == std::string::npos) {
    last_error_ = "squeue: " + FirstLine(out.output);
    return true;
  }
  last_error_.clear();
  counts_ = ParseSqueue(out.exit_code == 0 ? out.output : "");
  return true;
}

std::string SlurmArray::Describe() const {
  if (job_id_.empty()) return "slurm: not submitted";
  if (cancelled_) return fmt::format("slurm {}: cancelled", job_id_);
  if (!counts_.known) {
    return fmt::format("slurm {}: {} submitted", job_id_, settings_.tasks);
  }
  std::string text = fmt::format("slurm {}: {} running, {} pending", job_id_,
                                 counts_.running, counts_.pending);
  if (counts_.other > 0) text += fmt::format(", {} other", counts_.other);
  if (!last_error_.empty()) text += " (squeue failed: last known)";
  return text;
}

bool SlurmArray::Cancel() {
  if (job_id_.empty() || cancelled_) return true;
  cancelled_ = true;
  CommandOutput out;
  try {
    out = runner_.Run({"scancel", job_id_});
  } catch (const std::exception& e) {
    last_error_ = e.what();
    return false;
  }
  if (out.exit_code != 0) {
    last_error_ = "scancel: " + FirstLine(out.output);
    return false;
  }
  return true;
}

}  // namespace mrsim

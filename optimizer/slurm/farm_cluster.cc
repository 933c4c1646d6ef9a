#include "optimizer/slurm/farm_cluster.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace mrsim {
namespace {

// 'text' for a POSIX shell.
std::string ShellQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

// The port of "tcpq://HOST:PORT[?...]", or -1.
int TcpqPort(const std::string& url) {
  const std::string scheme = "tcpq://";
  if (url.rfind(scheme, 0) != 0) return -1;
  const std::string rest = url.substr(scheme.size());
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos) return -1;
  const std::string port = rest.substr(colon + 1, rest.find('?') - colon - 1);
  try {
    std::size_t used = 0;
    const int p = std::stoi(port, &used);
    return used == port.size() ? p : -1;
  } catch (const std::exception&) {
    return -1;
  }
}

double Now() {
  return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

std::string WorkerLcmUrl(const FarmClusterOptions& o) {
  if (o.hub_port > 0 && !o.lcm_url.empty() &&
      TcpqPort(o.lcm_url) != o.hub_port) {
    throw std::invalid_argument(fmt::format(
        "--hub {} with --lcm-url {}: the hub serves tcpq://HOST:{}; give "
        "that URL or leave --lcm-url out",
        o.hub_port, o.lcm_url, o.hub_port));
  }
  if (!o.lcm_url.empty()) return o.lcm_url;
  if (o.hub_port > 0) return fmt::format("tcpq://{}:{}", o.host, o.hub_port);
  return "";
}

std::string WorkerCommandLine(const FarmClusterOptions& o) {
  std::string line = "exec " + ShellQuote(o.worker_program);
  const std::string url = WorkerLcmUrl(o);
  if (!url.empty()) line += " --lcm-url " + ShellQuote(url);
  line += " --prefix " + ShellQuote(o.prefix);
  line += " --threads \"${SLURM_CPUS_PER_TASK:-1}\"";
  if (!o.key_file.empty()) line += " --key-file " + ShellQuote(o.key_file);
  return line;
}

FarmCluster::FarmCluster(const FarmClusterOptions& o,
                         std::unique_ptr<SlurmRunner> runner,
                         const std::function<void(const std::string&)>& log)
    : runner_(std::move(runner)), log_(log) {
  const std::string worker_url = WorkerLcmUrl(o);
  master_url_ = o.lcm_url;
  if (o.hub_port > 0) {
    hub_ = std::make_unique<LcmHub>(o.hub_port, o.out_dir + "/hub.log");
    if (master_url_.empty()) {
      master_url_ = fmt::format("tcpq://127.0.0.1:{}", o.hub_port);
    }
    if (log_) {
      log_(fmt::format("LCM TCP hub on port {} (process {}); workers use {}",
                       o.hub_port, hub_->pid(), worker_url));
    }
  }
  if (o.slurm_tasks > 0) {
    const std::string logs = o.out_dir + "/slurm";
    std::filesystem::create_directories(logs);
    SlurmArraySettings s;
    s.tasks = o.slurm_tasks;
    s.options = o.slurm_options;
    s.job_name = "mrsim-worker-" + o.prefix;
    s.command = WorkerCommandLine(o);
    s.output = std::filesystem::absolute(logs).string() + "/worker-%A_%a.log";
    s.poll_interval = o.poll_interval;
    array_ = std::make_unique<SlurmArray>(*runner_, s);
    array_->Submit();
    if (log_) {
      log_(fmt::format(
          "submitted {} worker{} as Slurm array job {} (squeue -j {}); each "
          "joins when Slurm starts it, the run goes on with those running",
          o.slurm_tasks, o.slurm_tasks == 1 ? "" : "s", array_->job_id(),
          array_->job_id()));
    }
  }
}

FarmCluster::~FarmCluster() {
  CancelWorkers();
  hub_.reset();  // after the workers: they need it until they end
}

void FarmCluster::CancelWorkers() {
  if (!array_ || array_->cancelled()) return;
  const bool ok = array_->Cancel();
  if (!log_) return;
  try {
    log_(ok ? fmt::format("cancelled Slurm job {}", array_->job_id())
            : fmt::format("could not cancel Slurm job {} ({}); run scancel {}",
                          array_->job_id(), array_->last_error(),
                          array_->job_id()));
  } catch (...) {  // logging must not stop the clean-up
  }
}

std::string FarmCluster::ProgressNote() {
  if (!array_) return "";
  array_->Poll(Now());
  return " | " + array_->Describe();
}

}  // namespace mrsim

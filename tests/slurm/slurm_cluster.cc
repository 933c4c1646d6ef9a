#include "tests/slurm/slurm_cluster.h"

#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>

#include "tests/common/wait_until.h"

namespace fs = std::filesystem;

namespace mrsim::testing {
namespace {

const char* const kPrograms[] = {"munged", "slurmctld", "slurmd",
                                 "sbatch", "squeue",    "scancel",
                                 "sinfo",  "scontrol",  "java"};

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

// True when the process has ended: gone, or a zombie its parent (maybe
// not us: the daemons detach) has not reaped yet.
bool Ended(pid_t pid) {
  if (kill(pid, 0) != 0) return true;
  std::ifstream stat(fmt::format("/proc/{}/stat", pid));
  std::string text((std::istreambuf_iterator<char>(stat)),
                   std::istreambuf_iterator<char>());
  const auto paren = text.rfind(')');
  return paren == std::string::npos || paren + 2 >= text.size() ||
         text[paren + 2] == 'Z';
}

// The pid in a daemon's pid file, when that process still runs the
// expected program (a recycled pid is left alone).
pid_t LivePid(const std::string& pid_file) {
  std::ifstream in(pid_file);
  long pid = 0;
  if (!(in >> pid) || pid <= 1) return -1;
  std::ifstream comm(fmt::format("/proc/{}/comm", pid));
  std::string name;
  if (!(comm >> name) || Ended(static_cast<pid_t>(pid))) return -1;
  for (const char* p : {"munged", "slurmctld", "slurmd"}) {
    if (name.rfind(p, 0) == 0) return static_cast<pid_t>(pid);
  }
  return -1;
}

// Daemons are in /usr/sbin, which a user's PATH may lack.
std::string Program(const std::string& name) {
  const std::string found = FindOnPath(name);
  return found.empty() ? "/usr/sbin/" + name : found;
}

void StopByPidFile(const std::string& pid_file) {
  const pid_t pid = LivePid(pid_file);
  if (pid <= 0) return;
  kill(pid, SIGTERM);
  const auto gone = [pid] { return Ended(pid); };
  if (!WaitUntil(gone, 10.0, 0.05)) {
    kill(pid, SIGKILL);
    WaitUntil(gone, 5.0, 0.05);
  }
  fs::remove(pid_file);
}

}  // namespace

bool SlurmCluster::Available(std::string* why) {
  if (geteuid() != 0) {
    *why = "needs root (a Slurm cluster on this host)";
    return false;
  }
  for (const char* p : kPrograms) {
    if (!fs::exists(Program(p))) {
      *why = std::string("no ") + p +
             " (scripts/install_deps.sh installs slurm-wlm and munge)";
      return false;
    }
  }
  return true;
}

SlurmCluster::SlurmCluster(int port, int nodes)
    // Unix sockets' paths (munged's, slurmstepd's in the spool) have at
    // most 108 bytes: the cluster lives in a short folder of its own.
    : dir_(fmt::format("/tmp/mrsim-slurm-{}", port)),
      conf_(dir_ + "/slurm.conf") {
  fs::create_directories(dir_);
  const std::string munge = dir_ + "/munge";
  pid_files_.push_back(dir_ + "/slurmctld.pid");
  for (int n = 1; n <= nodes; ++n) {
    pid_files_.push_back(fmt::format("{}/slurmd-n{}.pid", dir_, n));
  }
  pid_files_.push_back(munge + "/munged.pid");
  StopAll();  // what a crashed run in this folder left
  for (const char* sub : {"state", "log"}) {
    fs::remove_all(dir_ + "/" + sub);
    fs::create_directories(dir_ + "/" + sub);
  }
  for (int n = 1; n <= nodes; ++n) {
    fs::remove_all(fmt::format("{}/spool/n{}", dir_, n));
    fs::create_directories(fmt::format("{}/spool/n{}", dir_, n));
  }
  // munged checks its folder and key: only root may write or read them.
  fs::remove_all(munge);
  fs::create_directories(munge);
  chmod(munge.c_str(), 0711);
  {
    std::random_device device;
    std::string key;
    for (int i = 0; i < 128; ++i) {
      key.push_back(static_cast<char>(device() & 0xff));
    }
    WriteText(munge + "/munge.key", key);
    chmod((munge + "/munge.key").c_str(), 0400);
  }
  WriteText(
      conf_,
      fmt::format(
          "ClusterName=mrsimtest\nSlurmctldHost=localhost\n"
          "SlurmctldPort={port}\nSlurmdPort={port1}\n"
          "AuthType=auth/munge\nCredType=cred/munge\n"
          "AuthInfo=socket={munge}/munge.socket\n"
          "SlurmUser=root\nSlurmdUser=root\n"
          "StateSaveLocation={dir}/state\nSlurmdSpoolDir={dir}/spool/%n\n"
          "SlurmctldPidFile={dir}/slurmctld.pid\n"
          "SlurmdPidFile={dir}/slurmd-%n.pid\n"
          "SlurmctldLogFile={dir}/log/slurmctld.log\n"
          "SlurmdLogFile={dir}/log/slurmd-%n.log\n"
          "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
          "SelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
          "SchedulerType=sched/backfill\nMpiDefault=none\n"
          "ReturnToService=2\nJobCompType=jobcomp/none\n"
          "AccountingStorageType=accounting_storage/none\n"
          "InactiveLimit=0\nMinJobAge=5\nKillWait=2\n"
          "NodeName=n[1-{nodes}] NodeHostname=localhost NodeAddr=127.0.0.1 "
          "Port=[{port1}-{portn}] CPUs=1 State=UNKNOWN\n"
          "PartitionName=debug Nodes=n[1-{nodes}] Default=YES "
          "MaxTime=INFINITE State=UP\n",
          fmt::arg("port", port), fmt::arg("port1", port + 1),
          fmt::arg("portn", port + nodes), fmt::arg("nodes", nodes),
          fmt::arg("dir", dir_), fmt::arg("munge", munge)));
  setenv("SLURM_CONF", conf_.c_str(), 1);
  const auto start = [&](const std::vector<std::string>& argv) {
    std::vector<std::string> args = argv;
    args[0] = Program(args[0]);
    const CommandOutput out = RunForOutput(args, 30.0);
    if (out.exit_code != 0) {
      throw std::runtime_error(fmt::format("{} failed ({}): {}\n{}", argv[0],
                                           out.exit_code, out.output, Logs()));
    }
  };
  try {
    // Each daemon forks into the background and writes its pid file.
    start({"munged", "--force", "--socket=" + munge + "/munge.socket",
           "--key-file=" + munge + "/munge.key",
           "--pid-file=" + munge + "/munged.pid",
           "--log-file=" + munge + "/munged.log",
           "--seed-file=" + munge + "/munged.seed"});
    start({"slurmctld", "-f", conf_});
    for (int n = 1; n <= nodes; ++n) {
      start({"slurmd", "-f", conf_, "-N", fmt::format("n{}", n)});
    }
    std::string last;
    const bool idle = WaitUntil(
        [&] {
          last = Run({"sinfo", "--noheader", "--format=%D %T"}).output;
          return last == fmt::format("{} idle\n", nodes);
        },
        60.0, 0.2);
    if (!idle) {
      throw std::runtime_error("the nodes did not become idle: sinfo says '" +
                               last + "'\n" + Logs());
    }
  } catch (...) {
    StopAll();
    throw;
  }
}

SlurmCluster::~SlurmCluster() { StopAll(); }

void SlurmCluster::StopAll() {
  // Jobs first: a job's processes belong to slurmstepd, which outlives
  // slurmd; cancelled, they end with it.
  if (LivePid(dir_ + "/slurmctld.pid") > 0) {
    try {
      Run({"scancel", "--full", "--user=root"});
      WaitUntil(
          [&] {
            return Run({"squeue", "--noheader", "--format=%i"}).output.empty();
          },
          20.0, 0.2);
    } catch (const std::exception&) {  // stop the daemons all the same
    }
  }
  for (const std::string& f : pid_files_) StopByPidFile(f);
}

CommandOutput SlurmCluster::Run(const std::vector<std::string>& argv) const {
  return RunForOutput(argv, 30.0);
}

std::string SlurmCluster::Tasks(const std::string& job) const {
  const CommandOutput out = Run(
      {"squeue", "--noheader", "--array", "--jobs=" + job, "--format=%i %T"});
  return out.exit_code == 0 ? out.output : "";
}

std::string SlurmCluster::Logs() const {
  std::string text;
  for (const auto& entry : fs::directory_iterator(dir_ + "/log")) {
    const std::string log = ReadFileText(entry.path().string());
    text += "--- " + entry.path().filename().string() + " (end)\n" +
            log.substr(log.size() > 2000 ? log.size() - 2000 : 0);
  }
  return text;
}

}  // namespace mrsim::testing

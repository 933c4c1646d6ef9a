#include "tests/farm_net/farm_rig.h"

#include <fmt/format.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mrsim::testing {
namespace {

namespace fs = std::filesystem;
constexpr const char* kPrefix = "farmrig";
constexpr const char* kCgroupRoot = "/sys/fs/cgroup/cpu";
constexpr const char* kRmemMax = "/proc/sys/net/core/rmem_max";

int Run(const std::string& cmd) {
  const int rc = std::system((cmd + " >/dev/null 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

void Must(const std::string& cmd) {
  if (Run(cmd) != 0) throw std::runtime_error("farm rig: failed: " + cmd);
}

std::string Capture(const std::string& cmd) {
  std::string out;
  if (FILE* f = popen((cmd + " 2>/dev/null").c_str(), "r")) {
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
    pclose(f);
  }
  return out;
}

std::int64_t ReadRmemMax() {
  std::ifstream f(kRmemMax);
  std::int64_t bytes = 0;
  if (!(f >> bytes) || bytes < 0) return 0;
  return bytes;
}

// The value is the machine's, writable only from its first network
// namespace (a test may run inside another, e.g. under netns-run).
void WriteRmemMax(std::int64_t bytes) {
  { std::ofstream(kRmemMax) << bytes; }
  if (ReadRmemMax() == bytes) return;
  Run(fmt::format("nsenter --net=/proc/1/ns/net sh -c 'echo {} > {}'", bytes,
                  kRmemMax));
}

std::string NodeNs(const std::string& tag, int node) {
  return fmt::format("{}n{}", tag, node);
}
std::string BridgeNs(const std::string& tag) { return tag + "br"; }

// Kills what still runs in a namespace (only rig namespaces: processes a
// rig test started) and deletes it.
void RemoveNs(const std::string& ns) {
  std::istringstream pids(Capture("ip netns pids " + ns));
  int pid;
  while (pids >> pid) kill(pid, SIGKILL);
  Run("ip netns del " + ns);
}

// The pid in a rig name: farmrig<pid>x...
int CreatorPid(const std::string& name) {
  if (name.rfind(kPrefix, 0) != 0) return -1;
  return std::atoi(name.c_str() + std::string(kPrefix).size());
}

}  // namespace

bool FarmRig::Available(std::string* why) {
  if (geteuid() != 0) {
    *why =
        "the farm_net tests need root (network namespaces, a bridge, "
        "nftables, cgroups); run them as root";
    return false;
  }
  const std::string probe = fmt::format("{}{}probe", kPrefix, getpid());
  if (Run("ip netns add " + probe) != 0) {
    *why = "cannot create a network namespace (ip netns add failed)";
    return false;
  }
  const bool bridge = Run("ip -n " + probe + " link add br0 type bridge") == 0;
  Run("ip netns del " + probe);
  if (!bridge) {
    *why = "cannot create a bridge in a network namespace";
    return false;
  }
  if (Run("nft --version") != 0) {
    *why = "nft (package nftables) is missing: scripts/install_deps.sh";
    return false;
  }
  return true;
}

void FarmRig::CleanupStale() {
  std::istringstream list(Capture("ip netns list"));
  std::string line;
  while (std::getline(list, line)) {
    const std::string name = line.substr(0, line.find(' '));
    const int pid = CreatorPid(name);
    if (pid > 0 && pid != getpid() && kill(pid, 0) != 0) RemoveNs(name);
  }
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(kCgroupRoot, ec)) {
    const std::string name = e.path().filename().string();
    const int pid = CreatorPid(name);
    if (pid > 0 && pid != getpid() && kill(pid, 0) != 0) {
      for (const auto& sub : fs::directory_iterator(e.path(), ec)) {
        if (sub.is_directory()) rmdir(sub.path().c_str());
      }
      rmdir(e.path().c_str());
    }
  }
}

bool FarmRig::DelayAvailable(std::string* why) {
  if (!Available(why)) return false;
  if (access("/dev/net/tun", R_OK | W_OK) != 0) {
    *why = "no /dev/net/tun: delayed links need TAP devices";
    return false;
  }
  return true;
}

FarmRig::FarmRig(int nodes, const RigOptions& options)
    : tag_(fmt::format("{}{}x{}", kPrefix, getpid(),
                       std::rand() % 100000)),  // unique within the process
      nodes_(nodes),
      partitioned_(static_cast<size_t>(nodes), false) {
  CleanupStale();
  const std::string br = BridgeNs(tag_);
  try {
    Must("ip netns add " + br);
    Must("ip -n " + br + " link set lo up");
    // IGMP snooping with a querier, as on a managed switch.
    Must("ip -n " + br +
         " link add br0 type bridge mcast_snooping 1 mcast_querier 1");
    Must("ip -n " + br + " link set br0 up");
    for (int k = 0; k < nodes_; ++k) {
      const std::string ns = NodeNs(tag_, k);
      Must("ip netns add " + ns);
      const LinkDelay delay = static_cast<size_t>(k) < options.delays.size()
                                  ? options.delays[static_cast<size_t>(k)]
                                  : LinkDelay{};
      if (delay.on()) {
        if (!relay_) relay_ = std::make_unique<DelayRelay>(options.seed);
        relay_->AddLink(br, fmt::format("p{}", k), ns, "eth0", delay);
      } else {
        Must(fmt::format(
            "ip -n {} link add p{} type veth peer name eth0 netns {}", br, k,
            ns));
      }
      Must(fmt::format("ip -n {} link set p{} master br0 up", br, k));
      Must("ip -n " + ns + " link set lo up");
      Must(fmt::format("ip -n {} addr add {}/24 dev eth0", ns, Address(k)));
      Must("ip -n " + ns + " link set eth0 multicast on up");
      Must("ip -n " + ns + " route add 224.0.0.0/4 dev eth0");
    }
    Nft();
  } catch (...) {
    relay_.reset();
    for (int k = 0; k < nodes_; ++k) RemoveNs(NodeNs(tag_, k));
    RemoveNs(br);
    throw;
  }
}

FarmRig::~FarmRig() {
  if (rmem_set_ > 0 && ReadRmemMax() == rmem_set_) {
    WriteRmemMax(rmem_restore_);
  }
  // Its TAP devices go with it, before their namespaces do.
  relay_.reset();
  for (int k = 0; k < nodes_; ++k) RemoveNs(NodeNs(tag_, k));
  RemoveNs(BridgeNs(tag_));
  for (auto it = cgroups_.rbegin(); it != cgroups_.rend(); ++it) {
    rmdir(it->c_str());
  }
  rmdir(fmt::format("{}/{}", kCgroupRoot, tag_).c_str());
}

std::vector<std::string> FarmRig::In(int node,
                                     std::vector<std::string> argv) const {
  std::vector<std::string> out = {"/usr/bin/env", "ip", "netns", "exec",
                                  NodeNs(tag_, node)};
  out.insert(out.end(), argv.begin(), argv.end());
  return out;
}

std::string FarmRig::Address(int node) const {
  return fmt::format("10.77.0.{}", node + 1);
}

void FarmRig::Nft() {
  std::string rules =
      "table bridge farmrig {\n chain forward {\n"
      "  type filter hook forward priority 0; policy accept;\n";
  for (int k = 0; k < nodes_; ++k) {
    if (partitioned_[static_cast<size_t>(k)]) {
      rules +=
          fmt::format("  iifname \"p{0}\" drop\n  oifname \"p{0}\" drop\n", k);
    }
  }
  if (loss_ > 0) {
    rules += fmt::format("  numgen random mod 100 < {} drop\n", loss_);
  }
  rules += " }\n}\n";
  const std::string br = BridgeNs(tag_);
  Run("ip netns exec " + br + " nft delete table bridge farmrig");
  const std::string file = fmt::format("/tmp/{}.nft", tag_);
  { std::ofstream(file) << rules; }
  Must("ip netns exec " + br + " nft -f " + file);
  std::remove(file.c_str());
}

void FarmRig::SetLoss(int percent) {
  loss_ = percent;
  Nft();
}

void FarmRig::SetPartitioned(int node, bool on) {
  partitioned_.at(static_cast<size_t>(node)) = on;
  Nft();
}

void FarmRig::SetPortUp(int node, bool up) {
  Must(fmt::format("ip -n {} link set p{} {}", BridgeNs(tag_), node,
                   up ? "up" : "down"));
}

void FarmRig::CapCpu(int pid, double share) {
  const std::string root = fmt::format("{}/{}", kCgroupRoot, tag_);
  const std::string dir = fmt::format("{}/p{}", root, pid);
  std::error_code ec;
  if (!fs::exists(kCgroupRoot, ec)) return;  // no cpu controller: uncapped
  fs::create_directories(dir, ec);
  if (ec) return;
  cgroups_.push_back(dir);
  std::ofstream(dir + "/cpu.cfs_period_us") << 10000;
  std::ofstream(dir + "/cpu.cfs_quota_us") << static_cast<int>(share * 1e4);
  std::ofstream(dir + "/cgroup.procs") << pid;
  // One CPU per capped process (round robin): the quota of a 10 ms period
  // (2 ms at 0.2) is less than the kernel's bandwidth slice (5 ms), so a
  // process on two CPUs lets the thread that asks first (the episode)
  // take all of it, and its other threads (the one that handles LCM) can
  // starve for seconds. On one CPU they share one run queue fairly.
  const int cpus = std::max(1, static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN)));
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<int>(cgroups_.size() - 1) % cpus, &set);
  sched_setaffinity(pid, sizeof set, &set);  // threads made later inherit it
  for (const auto& task :
       fs::directory_iterator(fmt::format("/proc/{}/task", pid), ec)) {
    sched_setaffinity(std::atoi(task.path().filename().c_str()), sizeof set,
                      &set);
  }
}

RelayCounters FarmRig::relay_counters() const {
  return relay_ ? relay_->counters() : RelayCounters{};
}

std::int64_t FarmRig::RaiseReceiveBufferMax(std::int64_t bytes) {
  const std::int64_t before = ReadRmemMax();
  if (before <= 0 || before >= bytes) return before;
  WriteRmemMax(bytes);
  if (ReadRmemMax() == bytes) {
    if (rmem_set_ == 0) rmem_restore_ = before;
    rmem_set_ = bytes;
  }
  return before;
}

}  // namespace mrsim::testing

// A farm of "hosts" for tests: one network namespace per node (a master
// and N workers) joined by a Linux bridge that lives in a namespace of its
// own, so no address or interface of this machine is touched. Faults are
// made on the bridge: packet loss with nftables, partitions, port flaps;
// workers can be capped to a share of a CPU (cgroup v1). Needs root: use
// FarmRig::Available() and GTEST_SKIP otherwise. Everything is torn down
// by the destructor, and rigs left by a crashed test are removed when the
// next one starts (names carry the creating pid). Delay and jitter (no
// netem in this kernel) come from a user-space relay (delay_relay.h) on
// the links of the nodes that ask for them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tests/farm_net/delay_relay.h"

namespace mrsim::testing {

struct RigOptions {
  // Delay and jitter on node k's link to the bridge (both ways), by node;
  // nodes past the end or with no delay get a plain veth pair. A delayed
  // link is a pair of TAP devices, eth0 in the node and p<k> on the bridge,
  // joined by the rig's DelayRelay.
  std::vector<LinkDelay> delays;
  std::uint64_t seed = 1;  // of the relay's per-frame draws
};

class FarmRig {
 public:
  // True when namespaces can be made here; otherwise `why` says why not.
  static bool Available(std::string* why);
  // True when delayed links can be made too (TAP devices).
  static bool DelayAvailable(std::string* why);
  // Removes farmrig* namespaces and cgroups whose creating process is gone.
  static void CleanupStale();

  // `nodes` namespaces: node 0 is the master's (10.77.0.1), node k a
  // worker's (10.77.0.k+1). Throws naming the command that failed.
  explicit FarmRig(int nodes, const RigOptions& options = {});
  ~FarmRig();
  FarmRig(const FarmRig&) = delete;
  FarmRig& operator=(const FarmRig&) = delete;

  int nodes() const { return nodes_; }
  // argv prefixed to run a program inside node k's namespace.
  std::vector<std::string> In(int node, std::vector<std::string> argv) const;
  std::string Address(int node) const;
  // Drops this percentage of the frames the bridge forwards (0: none).
  void SetLoss(int percent);
  // Cuts node k off (both directions) or heals it.
  void SetPartitioned(int node, bool on);
  // Sets node k's bridge port down or up (up again loses its multicast
  // group membership on the snooping bridge).
  void SetPortUp(int node, bool up);
  // Caps a process to `share` of one CPU (0.2: a fifth), in 10 ms periods
  // (a slow host, not one that runs at full speed and then stops for
  // 80 ms as the default 100 ms period does), pinned to one CPU (round
  // robin over the machine's).
  void CapCpu(int pid, double share);
  // Raises net.core.rmem_max to at least `bytes` for the rig's life (the
  // farm asks for 4 MB socket buffers; a stock host allows 208 KB). The
  // value is one for the whole machine (read-only inside a namespace), so
  // the destructor puts the old one back unless someone changed it
  // meanwhile. Returns the value found (0: could not read it); it stays
  // when the process cannot write it (inside a network namespace of its
  // own, without access to the machine's).
  std::int64_t RaiseReceiveBufferMax(std::int64_t bytes);
  // What the delay relay did so far (zeros without delayed links).
  RelayCounters relay_counters() const;

 private:
  void Nft();

  std::string tag_;
  int nodes_;
  std::vector<std::string> cgroups_;
  int loss_ = 0;
  std::vector<bool> partitioned_;
  std::int64_t rmem_restore_ = 0, rmem_set_ = 0;
  std::unique_ptr<DelayRelay> relay_;  // closed before the namespaces go
};

}  // namespace mrsim::testing

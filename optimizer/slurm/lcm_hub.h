// LCM's TCP hub (`java -cp lcm.jar lcm.lcm.TCPService PORT`, the server
// behind tcpq:// URLs), started by mrsim-opt --hub for a farm whose hosts
// share no multicast (a cluster's nodes). Up once it accepts a connection;
// stopped (SIGTERM, then SIGKILL) when destroyed.
#pragma once

#include <memory>
#include <string>

#include "common/subprocess.h"

namespace mrsim {

class LcmHub {
 public:
  static constexpr const char* kJar = "/usr/share/java/lcm.jar";

  // Starts the hub on `port`, its output going to `log_path`, and waits up
  // to timeout_s until it accepts connections on 127.0.0.1. Throws
  // std::runtime_error naming what failed (no java, no lcm.jar, the port
  // taken: the hub's own words from its log).
  LcmHub(int port, const std::string& log_path, double timeout_s = 20.0);
  ~LcmHub();
  LcmHub(const LcmHub&) = delete;
  LcmHub& operator=(const LcmHub&) = delete;

  int port() const { return port_; }
  pid_t pid() const { return process_->pid(); }
  bool running() { return process_->running(); }

 private:
  int port_;
  std::unique_ptr<Subprocess> process_;
};

// True when something accepts a TCP connection on 127.0.0.1:port now.
bool TcpPortAccepts(int port);

}  // namespace mrsim

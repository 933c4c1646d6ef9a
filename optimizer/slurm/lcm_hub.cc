#include "optimizer/slurm/lcm_hub.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/command_output.h"

namespace mrsim {

bool TcpPortAccepts(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool ok =
      connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  close(fd);
  return ok;
}

LcmHub::LcmHub(int port, const std::string& log_path, double timeout_s)
    : port_(port) {
  if (port < 1 || port > 65535) {
    throw std::runtime_error(
        fmt::format("--hub {}: expected a TCP port 1..65535", port));
  }
  const std::string java = FindOnPath("java");
  if (java.empty()) {
    throw std::runtime_error(
        "--hub: no java on PATH (LCM's TCP hub is Java; install "
        "default-jre-headless)");
  }
  if (!std::filesystem::exists(kJar)) {
    throw std::runtime_error(std::string("--hub: no ") + kJar +
                             " (install liblcm-java)");
  }
  if (TcpPortAccepts(port)) {
    throw std::runtime_error(fmt::format(
        "--hub {}: something already listens on that port (another hub? "
        "then leave --hub out and give --lcm-url tcpq://HOST:{})",
        port, port));
  }
  SpawnOptions options = SpawnOptions::ToFile(log_path);
  // Ctrl-C in the terminal must not end the hub before the workers are
  // cancelled: its owner stops it last.
  options.own_process_group = true;
  process_ = std::make_unique<Subprocess>(
      std::vector<std::string>{java, "-cp", kJar, "lcm.lcm.TCPService",
                               std::to_string(port)},
      options);
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (!TcpPortAccepts(port)) {
    // Waiting on the hub's exit is the pause between two tries: a hub
    // that fails (port taken) is seen at once.
    if (process_->Wait(0.05) >= 0 || Clock::now() > deadline) {
      process_->Stop(1.0);
      std::ifstream log(log_path);
      std::stringstream text;
      text << log.rdbuf();
      throw std::runtime_error(fmt::format(
          "--hub {}: LCM's TCP hub did not start ({}): {}", port,
          Clock::now() > deadline ? "no connection in time" : "it ended",
          text.str().substr(0, 400)));
    }
  }
}

LcmHub::~LcmHub() {
  if (process_) process_->Stop(3.0);
}

}  // namespace mrsim

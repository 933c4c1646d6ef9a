// mrsim-foxglove as a real program beside a real mrsim-sim, connected to
// with Foxglove's own client library (client_check.js: @foxglove/ws-protocol
// over ws): with each subprotocol name, serverInfo, channels with JSON
// Schemas, the scene, transforms equal to the states and time that never
// goes back; a client without the control token is refused a pause, one
// with it is not; a client that stops reading loses its oldest frames
// while the others are served as before; a camera's pictures reach the
// client as foxglove.RawImage, malformed ones are counted.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <regex>
#include <string>
#include <thread>

#include "camera/camera_image_codec.h"
#include "lcmtypes/runtime/message_key.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

// Why the client library cannot run, or "" when it can.
std::string NodeMissing() {
  if (!std::filesystem::exists(SourcePath(
          "tests/foxglove/node_modules/@foxglove/ws-protocol/package.json"))) {
    return "tests/foxglove/node_modules is missing: scripts/install_deps.sh "
           "installs it (npm ci in tests/foxglove)";
  }
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    return "node is not installed: scripts/install_deps.sh installs it";
  }
  return "";
}

std::string WriteSnake(const std::string& dir) {
  ChainOptions options;
  options.modules = 4;
  options.pattern = ChainPattern::kPitchYaw;
  options.name = "snake";
  Scenario scenario;
  scenario.robots.push_back(MakeChain(options));
  const std::string path = dir + "/snake.xml";
  WriteScenarioFile(scenario, path);
  return path;
}

// client_check.js's verdict: its exit status 0, its line on failure.
void ExpectClientCheck(const std::string& dir, const std::string& name,
                       const std::vector<std::string>& args) {
  std::vector<std::string> argv = {
      "/usr/bin/env", "node", SourcePath("tests/foxglove/client_check.js")};
  argv.insert(argv.end(), args.begin(), args.end());
  ChildProcess node(argv, dir + "/" + name + ".txt");
  EXPECT_EQ(node.Wait(120), 0) << name << ": " << node.Output();
}

// A Foxglove client on a raw socket with a tiny receive buffer: it reads
// only when told to (a client that stops reading), and sends what it is
// given (a hostile one).
class RawClient {
 public:
  explicit RawClient(int port) : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
    const int small = 4096;
    setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(
        connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    Send(
        "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n"
        "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
        "Sec-WebSocket-Version: 13\r\n"
        "Sec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n");
    std::string reply;
    char c = 0;
    pollfd p{fd_, POLLIN, 0};
    while (reply.find("\r\n\r\n") == std::string::npos &&
           poll(&p, 1, 30000) == 1 && read(fd_, &c, 1) == 1) {
      reply.push_back(c);
    }
    EXPECT_EQ(reply.rfind("HTTP/1.1 101", 0), 0u) << reply;
  }
  ~RawClient() { close(fd_); }

  // Reads (and drops) what arrives until the server closes the
  // connection (true) or timeout_s passes (false).
  bool WaitClosed(double timeout_s) {
    const auto end = std::chrono::steady_clock::now() +
                     std::chrono::duration<double>(timeout_s);
    char buf[65536];
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (poll(&p, 1, 100) != 1) continue;
      const ssize_t n = read(fd_, buf, sizeof buf);
      if (n <= 0) return true;
    }
    return false;
  }
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;

  // One masked text frame (a zero mask: the payload goes as it is).
  void SendText(const std::string& text) {
    std::string frame = "\x81";
    if (text.size() < 126) {
      frame.push_back(static_cast<char>(0x80 | text.size()));
    } else if (text.size() < 65536) {
      frame.push_back(static_cast<char>(0x80 | 126));
      frame.push_back(static_cast<char>(text.size() >> 8));
      frame.push_back(static_cast<char>(text.size() & 0xff));
    } else {
      frame.push_back(static_cast<char>(0x80 | 127));
      for (int k = 7; k >= 0; --k) {
        frame.push_back(static_cast<char>((text.size() >> (8 * k)) & 0xff));
      }
    }
    frame.append(4, '\0');
    Send(frame + text);
  }

 private:
  void Send(const std::string& bytes) {
    size_t sent = 0;
    while (sent < bytes.size()) {
      // MSG_NOSIGNAL: a server that closes first (as it must on a huge
      // frame) is a short write here, not a SIGPIPE that kills the test.
      const ssize_t n =
          send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return;  // the server closed first
      sent += static_cast<size_t>(n);
    }
  }
  int fd_;
};

class FoxgloveProcess : public ::testing::Test {
 protected:
  void Start(int port, const std::vector<std::string>& extra,
             const std::string& rate = "50") {
    dir_ = TempDir("foxglove_process_" + std::to_string(port));
    const std::string url = TestLcmUrl(port);
    sim_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("sim_core/sim_process/mrsim-sim"),
                                 WriteSnake(dir_), "--lcm-url", url, "--rate",
                                 rate},
        dir_ + "/sim.txt");
    std::vector<std::string> argv = {
        BinaryPath("foxglove/process/mrsim-foxglove"),
        "--lcm-url",
        url,
        "--port",
        "0",
        "--bind",
        "127.0.0.1"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    fox_ = std::make_unique<ChildProcess>(argv, dir_ + "/foxglove.txt");
    ASSERT_TRUE(fox_->WaitForOutput("listening on ws://", 30))
        << fox_->Output();
    std::smatch m;
    const std::string out = fox_->Output();
    ASSERT_TRUE(
        std::regex_search(out, m, std::regex("ws://127\\.0\\.0\\.1:(\\d+)")));
    port_ = std::stoi(m[1].str());
    ws_url_ = "ws://127.0.0.1:" + m[1].str() + "/";
  }

  std::string dir_;
  std::string ws_url_;
  int port_ = 0;
  std::unique_ptr<ChildProcess> sim_;
  std::unique_ptr<ChildProcess> fox_;
};

TEST_F(FoxgloveProcess, FoxgloveClientSeesTheRobotMoveWithEitherSubprotocol) {
  const std::string skip = NodeMissing();
  if (!skip.empty()) GTEST_SKIP() << skip;
  Start(8130, {});
  for (const std::string protocol :
       {"foxglove.websocket.v1", "foxglove.sdk.v1"}) {
    ExpectClientCheck(dir_, protocol, {"watch", ws_url_, protocol, "snake"});
  }
  EXPECT_EQ(fox_->Stop(10), 0) << fox_->Output();
  EXPECT_NE(fox_->Output().find("mrsim-foxglove: stopped: 2 connections"),
            std::string::npos)
      << fox_->Output();
}

TEST_F(FoxgloveProcess, OnlyAClientWithTheControlTokenMayPause) {
  const std::string skip = NodeMissing();
  if (!skip.empty()) GTEST_SKIP() << skip;
  const std::string key = TempDir("foxglove_process_key") + "/control.key";
  WriteKeyFile(key);
  Start(8131, {"--control-key", key});
  ExpectClientCheck(dir_, "no_token",
                    {"control", ws_url_, "foxglove.websocket.v1", "refused"});
  const std::string key_hex = [&] {
    std::string hex;
    for (const char c : ReadKeyFile(key)) {
      static const char* const kHex = "0123456789abcdef";
      hex.push_back(kHex[static_cast<unsigned char>(c) >> 4]);
      hex.push_back(kHex[static_cast<unsigned char>(c) & 15]);
    }
    return hex;
  }();
  ExpectClientCheck(
      dir_, "token",
      {"control", ws_url_ + "?token=" + key_hex, "foxglove.sdk.v1", "ok"});
  EXPECT_EQ(fox_->Stop(10), 0) << fox_->Output();
  EXPECT_NE(fox_->Output().find("1 service calls refused"), std::string::npos)
      << fox_->Output();
}

TEST_F(FoxgloveProcess, AClientThatReadsNothingLosesFramesOthersAreServed) {
  const std::string skip = NodeMissing();
  if (!skip.empty()) GTEST_SKIP() << skip;
  Start(8132, {}, "100");
  RawClient stuck(port_);
  // The scene, the transforms and (once heard) two JSON channels.
  stuck.SendText(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1},)"
                 R"({"id":2,"channelId":2},{"id":3,"channelId":3},)"
                 R"({"id":4,"channelId":4}]})");
  EXPECT_TRUE(fox_->WaitForOutput("oldest frames are dropped", 120))
      << fox_->Output();
  ExpectClientCheck(dir_, "beside_stuck",
                    {"watch", ws_url_, "foxglove.websocket.v1", "snake"});
  EXPECT_EQ(fox_->Stop(10), 0) << fox_->Output();
  EXPECT_EQ(fox_->Output().find(" 0 frames dropped"), std::string::npos)
      << fox_->Output();
}

TEST_F(FoxgloveProcess, FoxgloveClientGetsACamerasPicturesAsRawImages) {
  const std::string skip = NodeMissing();
  if (!skip.empty()) GTEST_SKIP() << skip;
  Start(8135, {});
  CameraImageHeader header;
  header.robot = "snake";
  header.name = "snake/sm0/camera0";
  header.sim_time = 1.0;
  CameraPicture picture{32, 24, std::vector<uint8_t>(32 * 24 * 3, 200)};
  const camera_image_t msg = EncodeCameraImage(header, picture);
  camera_image_t malformed = msg;
  malformed.width = 31;  // disagrees with its bytes
  lcm::LCM lcm(TestLcmUrl(8135));
  ASSERT_TRUE(lcm.good());
  ChildProcess node(
      {"/usr/bin/env", "node", SourcePath("tests/foxglove/client_check.js"),
       "image", ws_url_, "foxglove.websocket.v1", "snake"},
      dir_ + "/image.txt");
  // The camera publishes at its rate until the client has seen a picture
  // (pacing the publisher, not waiting on the client).
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (node.running() && std::chrono::steady_clock::now() < end) {
    lcm.publish("MRSIM_CAMERA_snake", &msg);
    lcm.publish("MRSIM_CAMERA_snake", &malformed);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(node.Wait(10), 0) << node.Output();
  EXPECT_NE(node.Output().find(R"("camera":{"topic":"/camera/snake/0",)"
                               R"("schemaName":"foxglove.RawImage"})"),
            std::string::npos)
      << node.Output();
  EXPECT_EQ(fox_->Stop(10), 0) << fox_->Output();
  // The malformed pictures are counted, never shown.
  EXPECT_TRUE(std::regex_search(
      fox_->Output(), std::regex("[1-9][0-9]* LCM messages malformed")))
      << fox_->Output();
}

TEST_F(FoxgloveProcess, HostileFramesAreRefusedCountedAndAHugeOneCloses) {
  Start(8133, {});
  RawClient hostile(port_);
  hostile.SendText("{not json");
  hostile.SendText(R"({"op":"launchMissiles"})");
  hostile.SendText(
      R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":99}]})");
  hostile.SendText(std::string(2 << 20, ' '));  // 2 MB
  EXPECT_TRUE(hostile.WaitClosed(60));
  EXPECT_EQ(fox_->Stop(10), 0) << fox_->Output();
  EXPECT_NE(fox_->Output().find("2 client messages malformed (1 unknown ops, "
                                "1 too big), 1 subscriptions"),
            std::string::npos)
      << fox_->Output();
}

}  // namespace
}  // namespace mrsim

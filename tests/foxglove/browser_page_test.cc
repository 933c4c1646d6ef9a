// mrsim-foxglove's browser page as a user opens it: headless Chromium
// loads http://HOST:PORT/ from a real mrsim-foxglove beside a real
// mrsim-sim (page_screenshot.js drives it over the DevTools protocol and
// waits until the page says it has drawn the robot), and the screenshot
// shows the robot in its colour on a canvas that is not blank, with sim
// time and the real-time factor filled in. A Pause from the page is
// carried out (the page is on this host); with a control key, the page
// shows the refusal unless its URL carries the key's token.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <stb/stb_image.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <regex>
#include <set>
#include <string>

#include "foxglove/control_access.h"
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

// The Chromium to drive, or "" (then `why` says what is missing).
std::string FindChromium(std::string& why) {
  if (!std::filesystem::exists(
          SourcePath("tests/foxglove/node_modules/ws/package.json")) ||
      std::system("node --version > /dev/null 2>&1") != 0) {
    why =
        "node or tests/foxglove/node_modules is missing: "
        "scripts/install_deps.sh installs them";
    return "";
  }
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (std::filesystem::exists(path)) return path;
  }
  why = "chromium is not installed: scripts/install_deps.sh installs it";
  return "";
}

// One plain HTTP request to 127.0.0.1:port; the whole reply (the server
// closes the connection after it), or what came before the deadline.
std::string HttpRequest(int port, const std::string& request) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string reply;
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
      write(fd, request.data(), request.size()) ==
          static_cast<ssize_t>(request.size())) {
    char buf[65536];
    pollfd p{fd, POLLIN, 0};
    while (poll(&p, 1, 30000) == 1) {
      const ssize_t n = read(fd, buf, sizeof buf);
      if (n <= 0) break;
      reply.append(buf, static_cast<size_t>(n));
    }
  }
  close(fd);
  return reply;
}

std::string Get(int port, const std::string& path) {
  return HttpRequest(port, "GET " + path +
                               " HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                               "Connection: close\r\n\r\n");
}

struct Png {
  int width = 0, height = 0;
  std::unique_ptr<unsigned char, decltype(&stbi_image_free)> rgb{
      nullptr, &stbi_image_free};
  const unsigned char* at(int x, int y) const {
    return rgb.get() + 3 * (static_cast<size_t>(y) * width + x);
  }
};

Png ReadPng(const std::string& path) {
  Png png;
  int channels = 0;
  png.rgb.reset(stbi_load(path.c_str(), &png.width, &png.height, &channels, 3));
  return png;
}

// The robot's orange (scene_model.cc: 0.95, 0.55, 0.15) as lit by the
// page: red high, green well below it, blue far below green. Neither the
// grey ground, the blue-grey background and panels, nor the grid is.
bool IsRobotOrange(const unsigned char* p) {
  return p[0] > 150 && p[1] + 30 < p[0] && p[2] + 40 < p[1];
}

class BrowserPage : public ::testing::Test {
 protected:
  void SetUp() override { chromium_ = FindChromium(skip_); }

  void Start(const std::vector<std::string>& extra) {
    dir_ = TempDir("foxglove_browser");
    ChainOptions options;
    options.modules = 4;
    options.pattern = ChainPattern::kPitchYaw;
    options.name = "snake";
    Scenario scenario;
    scenario.robots.push_back(MakeChain(options));
    WriteScenarioFile(scenario, dir_ + "/snake.xml");
    const std::string url = TestLcmUrl(8134);
    sim_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("sim_core/sim_process/mrsim-sim"),
                                 dir_ + "/snake.xml", "--lcm-url", url,
                                 "--rate", "50"},
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
    ASSERT_TRUE(fox_->WaitForOutput("the browser page: http://", 30))
        << fox_->Output();
    std::smatch m;
    const std::string out = fox_->Output();
    ASSERT_TRUE(std::regex_search(
        out, m,
        std::regex("the browser page: (http://127\\.0\\.0\\.1:\\d+/)")));
    page_url_ = m[1].str();
    port_ = std::stoi(page_url_.substr(page_url_.rfind(':') + 1));
  }

  // page_screenshot.js's exit status and its JSON line.
  int Screenshot(const std::string& png, const std::string& press,
                 std::string& line, const std::string& query = "") {
    std::vector<std::string> argv = {"/usr/bin/env"};
    if (!press.empty()) argv.push_back("PRESS=" + press);
    argv.insert(argv.end(),
                {"node", SourcePath("tests/foxglove/page_screenshot.js"),
                 chromium_, page_url_ + query, png, "900x600"});
    ChildProcess node(argv, png + ".txt");
    const int status = node.Wait(150);
    line = node.Output();
    return status;
  }

  std::string skip_;
  std::string chromium_;
  std::string dir_;
  std::string page_url_;
  int port_ = 0;
  std::unique_ptr<ChildProcess> sim_;
  std::unique_ptr<ChildProcess> fox_;
};

// Over a real socket, without a browser: the shipped files with their
// Content-Type, 404 for any other path, 405 for anything but GET.
TEST_F(BrowserPage, ServesOnlyItsFilesOverHttp) {
  if (!std::filesystem::exists(
          BinaryPath("foxglove/process/web/three.core.js"))) {
    GTEST_SKIP() << "three.js is not in the build: scripts/install_deps.sh "
                    "installs it (npm ci in foxglove/web), then rebuild";
  }
  Start({});
  std::string reply = Get(port_, "/");
  EXPECT_EQ(reply.rfind("HTTP/1.1 200", 0), 0u) << reply.substr(0, 200);
  EXPECT_NE(reply.find("Content-Type: text/html; charset=utf-8"),
            std::string::npos);
  EXPECT_NE(reply.find("<script type=\"module\" src=\"./mrsim_page.js\">"),
            std::string::npos);
  reply = Get(port_, "/three.core.js");
  EXPECT_EQ(reply.rfind("HTTP/1.1 200", 0), 0u) << reply.substr(0, 200);
  EXPECT_NE(reply.find("Content-Type: text/javascript; charset=utf-8"),
            std::string::npos);
  EXPECT_GT(reply.size(), 100000u);
  for (const char* path :
       {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd",
        "/web/index.html", "/CMakeLists.txt"}) {
    reply = Get(port_, path);
    EXPECT_EQ(reply.rfind("HTTP/1.1 404", 0), 0u) << path << ": " << reply;
    EXPECT_EQ(reply.find("root:"), std::string::npos) << path;
  }
  reply = HttpRequest(port_,
                      "POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: "
                      "0\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(reply.rfind("HTTP/1.1 405", 0), 0u) << reply;
}

TEST_F(BrowserPage, AScreenshotShowsTheRobotSimTimeAndRealTimeFactor) {
  if (chromium_.empty()) GTEST_SKIP() << skip_;
  Start({});
  const std::string png_path = dir_ + "/page.png";
  std::string line;
  ASSERT_EQ(Screenshot(png_path, "", line), 0) << line;
  EXPECT_NE(line.find(R"("title":"mrsim: live")"), std::string::npos) << line;
  EXPECT_TRUE(std::regex_search(line, std::regex(R"("simtime":"\d+\.\d\d s")")))
      << line;
  EXPECT_TRUE(std::regex_search(line, std::regex(R"("rtf":"\d+\.\d\d")")))
      << line;
  EXPECT_NE(line.find(R"("follow":"snake")"), std::string::npos) << line;

  const Png png = ReadPng(png_path);
  ASSERT_NE(png.rgb, nullptr) << png_path << ": " << stbi_failure_reason();
  ASSERT_EQ(png.width, 900);
  ASSERT_EQ(png.height, 600);
  int orange = 0;
  std::set<int> colours;
  for (int y = 0; y < png.height; ++y) {
    for (int x = 0; x < png.width; ++x) {
      const unsigned char* p = png.at(x, y);
      if (IsRobotOrange(p)) ++orange;
      if (colours.size() < 1000) colours.insert(p[0] << 16 | p[1] << 8 | p[2]);
    }
  }
  // Four modules (eight frames) a couple of metres away: thousands of
  // pixels; the plot's orange line alone is a few hundred.
  EXPECT_GT(orange, 1500) << png_path;
  EXPECT_GT(colours.size(), 50u) << png_path << ": a blank page";
}

TEST_F(BrowserPage, ItsPauseButtonPausesTheSimulator) {
  if (chromium_.empty()) GTEST_SKIP() << skip_;
  Start({});
  std::string line;
  ASSERT_EQ(Screenshot(dir_ + "/paused.png", "pause", line), 0) << line;
  EXPECT_NE(line.find(R"("message":"/mrsim/pause: done")"), std::string::npos)
      << line;
  EXPECT_EQ(fox_->Stop(10), 0) << fox_->Output();
  EXPECT_NE(fox_->Output().find(" 0 service calls refused"), std::string::npos)
      << fox_->Output();
}

TEST_F(BrowserPage, WithAControlKeyItShowsTheRefusalUnlessItsUrlHasTheToken) {
  if (chromium_.empty()) GTEST_SKIP() << skip_;
  const std::string key = TempDir("foxglove_browser_key") + "/control.key";
  WriteKeyFile(key);
  Start({"--control-key", key});
  std::string line;
  ASSERT_EQ(Screenshot(dir_ + "/refused.png", "pause", line), 0) << line;
  EXPECT_TRUE(std::regex_search(
      line, std::regex(R"("message":"/mrsim/pause: refused: this client may )"
                       R"(not control)")))
      << line;
  ASSERT_EQ(Screenshot(dir_ + "/token.png", "pause", line,
                       "?token=" + foxglove::ControlTokenFromKeyFile(key)),
            0)
      << line;
  EXPECT_NE(line.find(R"("message":"/mrsim/pause: done")"), std::string::npos)
      << line;
  EXPECT_EQ(fox_->Stop(10), 0) << fox_->Output();
  EXPECT_NE(fox_->Output().find(" 1 service calls refused"), std::string::npos)
      << fox_->Output();
}

}  // namespace
}  // namespace mrsim

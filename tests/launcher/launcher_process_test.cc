// Runs the real `mrsim` program on launch files of shell processes.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/videoio.hpp>
#include <regex>
#include <thread>

#include "common/version.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

std::string WriteLaunch(const std::string& dir, const std::string& text) {
  const std::string path = dir + "/test.launch";
  std::ofstream(path) << text;
  return path;
}

TEST(Launcher, RequiredProcessEndingStopsTheOthersAndPrefixesOutput) {
  const std::string dir = TempDir("launcher_required");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="forever" program="/bin/sh"
           args="-c 'echo up; trap &quot;echo flushed; exit 0&quot; INT TERM; while true; do sleep 0.05; done'"/>
  <process name="short" program="/bin/sh" required="true" delay="0.3"
           args="-c 'echo hello from short; exit 0'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  const int code = mrsim.Wait(30);
  const std::string out = mrsim.Output();
  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find("[short "), std::string::npos) << out;
  EXPECT_NE(out.find("hello from short"), std::string::npos) << out;
  EXPECT_NE(out.find("] up"), std::string::npos) << out;
  // The long-running one was told to stop and flushed.
  EXPECT_NE(out.find("flushed"), std::string::npos) << out;
}

TEST(Launcher, RequiredExitIsNoticedWhileAQuietSiblingHoldsItsPipe) {
  // 8 KB (two full reads), then silence: a blocking read of the quiet
  // child's output would keep the launcher from noticing the exit.
  const std::string dir = TempDir("launcher_quiet_sibling");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="chatty" program="/bin/sh"
           args="-c 'yes 0123456789abcdef | head -c 8192; exec sleep 600'"/>
  <process name="short" program="/bin/sh" required="true" delay="0.2"
           args="-c 'echo bye'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  EXPECT_EQ(mrsim.Wait(30), 0) << mrsim.Output();
  const std::string out = mrsim.Output();
  EXPECT_NE(out.find("short ended, stopping the others"), std::string::npos)
      << out;
  // Every full line of the 8 KB was forwarded (512 lines of 16 + newline
  // minus the cut one).
  size_t lines = 0;
  for (size_t i = out.find("] 0123456789abcdef\n"); i != std::string::npos;
       i = out.find("] 0123456789abcdef\n", i + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 8192u / 17) << out;
}

TEST(Launcher, InterruptStopsEveryProcessCleanly) {
  const std::string dir = TempDir("launcher_interrupt");
  const std::string marker = dir + "/stopped";
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <arg name="marker" default=")" + marker + R"("/>
  <process name="a" program="/bin/sh"
           args="-c 'trap &quot;touch ${marker}.a; exit 0&quot; INT TERM; echo armed; while true; do sleep 0.05; done'"/>
  <process name="b" program="/bin/sh"
           args="-c 'trap &quot;touch ${marker}.b; exit 0&quot; INT TERM; echo armed; while true; do sleep 0.05; done'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  // Both have set their traps.
  ASSERT_TRUE(mrsim.WaitForOutput("[a     ] armed", 30)) << mrsim.Output();
  ASSERT_TRUE(mrsim.WaitForOutput("[b     ] armed", 30)) << mrsim.Output();
  mrsim.Signal(SIGINT);
  EXPECT_EQ(mrsim.Wait(30), 0) << mrsim.Output();
  EXPECT_TRUE(std::ifstream(marker + ".a").good()) << mrsim.Output();
  EXPECT_TRUE(std::ifstream(marker + ".b").good()) << mrsim.Output();
}

// mrsim-opt exits 130 when a stop leaves its run unfinished.
TEST(Launcher, AProcessSayingItWasInterruptedStillStopsCleanly) {
  const std::string dir = TempDir("launcher_exit130");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="opt" program="/bin/sh"
           args="-c 'tail -f /dev/null &amp; t=$!; trap &quot;kill $t; wait $t; exit 130&quot; INT TERM; echo armed; wait $t'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  ASSERT_TRUE(mrsim.WaitForOutput("armed", 30)) << mrsim.Output();
  mrsim.Signal(SIGINT);
  EXPECT_EQ(mrsim.Wait(30), 0) << mrsim.Output();
  // Stopped as asked: said so, not as "exited with code 130".
  EXPECT_NE(mrsim.Output().find("opt stopped"), std::string::npos)
      << mrsim.Output();
  EXPECT_EQ(mrsim.Output().find("exited with code 130"), std::string::npos)
      << mrsim.Output();
}

// A launch through LCM's TCP hub used to end with "Connection reset by
// peer", "re-connecting" and "hub: exited with code 130": the hub was
// stopped with its clients. Now the clients stop first, then the hub.
TEST(Launcher, ClientsStopBeforeTheirHubQuietly) {
  const std::string dir = TempDir("launcher_hub");
  int port = 7886;
  if (const char* offset = std::getenv("MRSIM_TEST_PORT_OFFSET")) {
    port += std::atoi(offset);
  }
  const std::string url = "tcpq://127.0.0.1:" + std::to_string(port);
  const std::string launch = WriteLaunch(
      dir, R"(<launch>
  <hub port=")" +
               std::to_string(port) + R"("/>
  <process name="sim" program=")" +
               BinaryPath("sim_core/sim_process/mrsim-sim") + R"(" args=")" +
               testing::SourcePath("scenarios/snake11.xml") +
               " --paused --lcm-url " + url +
               R"("/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  ASSERT_TRUE(mrsim.WaitForOutput("mrsim-sim: 1 robot(s)", 60))
      << mrsim.Output();
  mrsim.Signal(SIGINT);
  EXPECT_EQ(mrsim.Wait(60), 0) << mrsim.Output();
  const std::string out = mrsim.Output();
  for (const char* noise : {"Connection reset", "re-connecting",
                            "Connection refused", "exited with code 130"}) {
    EXPECT_EQ(out.find(noise), std::string::npos) << noise << "\n" << out;
  }
  const size_t sim_ended = out.find("] sim exited with code 0");
  const size_t hub_ended = out.find("] hub stopped");
  ASSERT_NE(sim_ended, std::string::npos) << out;
  ASSERT_NE(hub_ended, std::string::npos) << out;
  EXPECT_LT(sim_ended, hub_ended) << out;
}

TEST(Launcher, AnExit130NobodyAskedForIsAFailure) {
  const std::string dir = TempDir("launcher_own130");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="opt" program="/bin/sh" required="true" args="-c 'exit 130'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  EXPECT_EQ(mrsim.Wait(30), 1) << mrsim.Output();
}

TEST(Launcher, ReportsAProcessThatDies) {
  const std::string dir = TempDir("launcher_dies");
  // main ends only once the launcher has reaped crasher (kill -0 succeeds
  // on a zombie), so the report cannot race the end of the run.
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <arg name="pid" default=")" + dir + R"(/crasher.pid"/>
  <process name="crasher" program="/bin/sh"
           args="-c 'echo $$ > ${pid}.tmp; mv ${pid}.tmp ${pid}; exit 3'"/>
  <process name="main" program="/bin/sh" required="true"
           args="-c 'while [ ! -s ${pid} ] || kill -0 $(cat ${pid}) 2>/dev/null; do sleep 0.05; done'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  EXPECT_EQ(mrsim.Wait(30), 1);
  EXPECT_NE(mrsim.Output().find("crasher exited with code 3"),
            std::string::npos)
      << mrsim.Output();
}

// A viewer still rendering the frames it fell behind on when the simulator
// ends: with finish="..." it completes them and ends by itself; the
// launch waits for it instead of stopping it.
TEST(Launcher, AProcessMayFinishItsWorkAfterTheRequiredOneEnds) {
  const std::string dir = TempDir("launcher_finish");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <arg name="done" default=")" + dir + R"(/sim_done"/>
  <process name="view" program="/bin/sh" finish="60"
           args="-c 'while [ ! -e ${done} ]; do sleep 0.02; done; for i in 1 2 3 4 5 6 7 8 9 10; do echo frame $i; sleep 0.1; done; echo wrote the whole video'"/>
  <process name="ticker" program="/bin/sh"
           args="-c 'trap &quot;echo ticker stopped; exit 0&quot; INT TERM; while true; do sleep 0.05; done'"/>
  <process name="sim" program="/bin/sh" required="true" delay="0.2"
           args="-c 'touch ${done}; echo sim done'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  EXPECT_EQ(mrsim.Wait(60), 0) << mrsim.Output();
  const std::string out = mrsim.Output();
  EXPECT_NE(out.find("sim ended; letting view (up to 60 s) finish"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("frame 10"), std::string::npos) << out;
  EXPECT_NE(out.find("wrote the whole video"), std::string::npos) << out;
  EXPECT_NE(out.find("view exited with code 0"), std::string::npos) << out;
  // The others are stopped at once, before the finisher is done.
  EXPECT_NE(out.find("ticker stopped"), std::string::npos) << out;
  EXPECT_LT(out.find("ticker stopped"), out.find("wrote the whole video"))
      << out;
}

TEST(Launcher, AProcessThatDoesNotFinishInTimeIsStopped) {
  const std::string dir = TempDir("launcher_finish_late");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="view" program="/bin/sh" finish="0.5"
           args="-c 'trap &quot;echo view stopped; exit 0&quot; INT TERM; echo armed; while true; do sleep 0.05; done'"/>
  <process name="sim" program="/bin/sh" required="true" delay="0.2"
           args="-c 'echo sim done'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  EXPECT_EQ(mrsim.Wait(60), 0) << mrsim.Output();
  const std::string out = mrsim.Output();
  EXPECT_NE(out.find("view has not finished after 0.5 s, stopping it"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("view stopped"), std::string::npos) << out;
}

// Ctrl-C while a process is finishing stops it at once, not after its
// finish time.
TEST(Launcher, InterruptWhileFinishingStopsAtOnce) {
  const std::string dir = TempDir("launcher_finish_interrupt");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="view" program="/bin/sh" finish="600"
           args="-c 'trap &quot;echo view stopped; exit 0&quot; INT TERM; echo armed; while true; do sleep 0.05; done'"/>
  <process name="sim" program="/bin/sh" required="true" delay="0.2"
           args="-c 'echo sim done'"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  ASSERT_TRUE(mrsim.WaitForOutput("letting view (up to 600 s) finish", 30))
      << mrsim.Output();
  mrsim.Signal(SIGINT);
  // Well before the 600 s: the whole test's deadline.
  EXPECT_EQ(mrsim.Wait(60), 0) << mrsim.Output();
  EXPECT_NE(mrsim.Output().find("view stopped"), std::string::npos)
      << mrsim.Output();
}

// The demo as a user runs it, with a viewer far slower than the run: at
// 120 frames per simulated second of 640x480 software rendering it falls
// behind (as a loaded machine makes it at 30), and the video must still
// cover the whole run, from its first state (the simulator starts only
// once the viewer, the logger and the controller say they listen, however
// long the viewer takes to set up EGL) to its end (the viewer may finish
// after the simulator).
TEST(DemoLaunch, TheVideoCoversTheWholeRunWhenTheViewerFallsBehind) {
  const std::string dir = TempDir("demo_launch_slow_viewer");
  const double duration = 3.0;
  const double fps = 120.0;
  ChildProcess mrsim(
      {BinaryPath("launcher/mrsim"), "launch", SourcePath("launch/demo.launch"),
       "--set", "out=" + dir, "--set", "duration=3", "--set", "fps=120",
       "--set", "lcm_url=" + TestLcmUrl(7887)},
      dir + "/out.txt");
  ASSERT_EQ(mrsim.Wait(600), 0) << mrsim.Output();
  const std::string out = mrsim.Output();
  // The logger may have ended by itself before the launcher saw the
  // simulator go; the viewer, behind, is still at work then.
  EXPECT_NE(out.find("view (up to 600 s)"), std::string::npos) << out;
  EXPECT_NE(out.find("the simulator stopped (--exit-with-sim)"),
            std::string::npos)
      << out;
  cv::VideoCapture video(dir + "/demo.mp4");
  ASSERT_TRUE(video.isOpened()) << out;
  const double frames = video.get(cv::CAP_PROP_FRAME_COUNT);
  // Frame k shows time k / fps.
  const std::smatch first = [&] {
    std::smatch m;
    std::regex_search(out, m,
                      std::regex(R"(first index (\d+), last at ([0-9.]+) s)"));
    return m;
  }();
  ASSERT_EQ(first.size(), 3u) << out;
  EXPECT_EQ(std::stoi(first[1]), 0) << out;
  EXPECT_NEAR(std::stod(first[2]), duration, 0.02) << out;
  EXPECT_GE(frames, duration * fps) << out;
  // The logger heard the first state too.
  EXPECT_NE(out.find("mrsim.robot_state_t, 301 messages, 301 rows, seq 0..300"),
            std::string::npos)
      << out;
  EXPECT_TRUE(std::ifstream(dir + "/final.checkpoint").good()) << out;
  EXPECT_TRUE(std::ifstream(dir + "/front_force.png").good()) << out;
}

TEST(Launcher, UnknownProgramStartsNothingAndExitsTwo) {
  const std::string dir = TempDir("launcher_unknown");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="a" program="/bin/sh" args="-c 'touch )" +
                                                  dir +
                                                  R"(/started'"/>
  <process name="b" program="mrsim-no-such-program"/>
</launch>)");
  ChildProcess mrsim({BinaryPath("launcher/mrsim"), "launch", launch},
                     dir + "/out.txt");
  EXPECT_EQ(mrsim.Wait(30), 2);
  // Named where the file says it, each folder looked in once.
  const std::string out = mrsim.Output();
  EXPECT_NE(out.find("test.launch:3: process 'b': cannot find program "
                     "'mrsim-no-such-program'"),
            std::string::npos)
      << out;
  const std::string bin = "\n  " + BinaryPath("bin") + "\n";
  EXPECT_EQ(out.find(bin), out.rfind(bin)) << out;
  EXPECT_FALSE(std::ifstream(dir + "/started").good());
}

TEST(Launcher, WithoutLeavesAProcessOut) {
  const std::string dir = TempDir("launcher_without");
  const std::string launch = WriteLaunch(dir, R"(<launch>
  <process name="a" program="/bin/sh" required="true" args="-c 'echo A-ran'"/>
  <process name="b" program="/bin/sh" args="-c 'echo B-ran'"/>
</launch>)");
  ChildProcess mrsim(
      {BinaryPath("launcher/mrsim"), "launch", launch, "--without", "b"},
      dir + "/out.txt");
  EXPECT_EQ(mrsim.Wait(30), 0);
  EXPECT_NE(mrsim.Output().find("A-ran"), std::string::npos);
  EXPECT_EQ(mrsim.Output().find("B-ran"), std::string::npos);
}

// Every program the README puts on the PATH (build/bin), and only those.
TEST(Programs, EveryProgramAnswersVersion) {
  const std::string dir = TempDir("programs_version");
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(BinaryPath("bin"))) {
    names.push_back(e.path().filename().string());
  }
  EXPECT_GE(names.size(), 13u);
  for (const std::string& name : names) {
    EXPECT_EQ(name.rfind("mrsim", 0), 0u) << name;
    ChildProcess p({BinaryPath("bin/" + name), "--version"},
                   dir + "/" + name + ".txt");
    EXPECT_EQ(p.Wait(30), 0) << name << ": " << p.Output();
    EXPECT_EQ(p.Output(), name + " " + kVersion + "\n") << name;
  }
}

}  // namespace
}  // namespace mrsim

#include "launcher/launch_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <fstream>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  // One folder per process (ctest runs one test in each): a second file
  // must not clear the first.
  static const std::string dir = testing::TempDir("launch_file");
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(LaunchFile, SubstitutesArgsAndOverrides) {
  const std::string path = WriteFile("a.launch", R"(<launch name="t">
  <arg name="out" default="outdir"/>
  <arg name="speed" default="2"/>
  <process name="sim" program="mrsim-sim" required="true"
           args="${launch_dir}/x.xml --speed ${speed} --out '${out}/a b'"/>
  <process name="viewer" program="mrsim-view" delay="0.5" enabled="false"
           finish="90"/>
</launch>)");
  const LaunchFile f = ReadLaunchFile(path, {{"speed", "4"}});
  ASSERT_EQ(f.processes.size(), 2u);
  EXPECT_EQ(f.name, "t");
  const auto& sim = f.processes[0];
  EXPECT_TRUE(sim.required);
  ASSERT_EQ(sim.args.size(), 5u);
  EXPECT_EQ(sim.args[0], f.variables.at("launch_dir") + "/x.xml");
  EXPECT_EQ(sim.args[2], "4");
  EXPECT_EQ(sim.args[4], "outdir/a b");
  EXPECT_FALSE(f.processes[1].enabled);
  EXPECT_DOUBLE_EQ(f.processes[1].delay_s, 0.5);
  EXPECT_DOUBLE_EQ(f.processes[1].finish_s, 90);
  EXPECT_DOUBLE_EQ(sim.finish_s, 0);  // stopped at once unless it says so
}

// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = getenv(name)) old_ = old, had_ = true;
    if (value) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (had_) {
      setenv(name_.c_str(), old_.c_str(), 1);
    } else {
      unsetenv(name_.c_str());
    }
  }

 private:
  std::string name_, old_;
  bool had_ = false;
};

TEST(LaunchFile, LcmDefaultUrlBeatsTheBundledDefaultAndSetBeatsBoth) {
  const std::string demo = testing::SourcePath("launch/demo.launch");
  const std::string mine = "udpm://239.255.76.67:7999?ttl=0";
  {
    ScopedEnv env("LCM_DEFAULT_URL", nullptr);
    EXPECT_EQ(ReadLaunchFile(demo, {}).variables.at("lcm_url"),
              "udpm://239.255.76.67:7667?ttl=0");
  }
  ScopedEnv env("LCM_DEFAULT_URL", mine.c_str());
  const LaunchFile f = ReadLaunchFile(demo, {});
  EXPECT_EQ(f.variables.at("lcm_url"), mine);
  for (const ProcessSpec& p : f.processes) {
    const auto it = std::find(p.args.begin(), p.args.end(), "--lcm-url");
    ASSERT_NE(it, p.args.end()) << p.name;
    EXPECT_EQ(*(it + 1), mine) << p.name;
  }
  EXPECT_EQ(ReadLaunchFile(demo, {{"lcm_url", "udpm://239.255.76.67:7001"}})
                .variables.at("lcm_url"),
            "udpm://239.255.76.67:7001");
  EXPECT_EQ(
      ReadLaunchFile(testing::SourcePath("launch/optimize_local.launch"), {})
          .variables.at("lcm_url"),
      mine);
  // A value the launch file gives explicitly is not the environment's.
  const std::string fixed = WriteFile("fixed.launch", R"(<launch>
  <arg name="lcm_url" default="udpm://239.255.76.67:7123?ttl=0"/>
  <process name="p" program="/bin/true" args="--lcm-url ${lcm_url}"/>
</launch>)");
  EXPECT_EQ(ReadLaunchFile(fixed, {}).processes[0].args[1],
            "udpm://239.255.76.67:7123?ttl=0");
}

TEST(LaunchFile, HubRunsLcmTcpService) {
  const std::string path = WriteFile("hub.launch", R"(<launch>
  <arg name="port" default="7903"/>
  <hub port="${port}"/>
  <process name="p" program="/bin/true"/>
</launch>)");
  const LaunchFile f = ReadLaunchFile(path, {});
  ASSERT_EQ(f.processes.size(), 2u);
  const ProcessSpec& hub = f.processes[0];
  EXPECT_EQ(hub.name, "hub");
  EXPECT_EQ(hub.program, "java");
  EXPECT_EQ(hub.args,
            (std::vector<std::string>{"-cp", "/usr/share/java/lcm.jar",
                                      "lcm.lcm.TCPService", "7903"}));
  EXPECT_FALSE(hub.required);
  EXPECT_EQ(hub.ready_port, 7903);  // what comes after waits for it
  const std::string bad = WriteFile("bad_hub.launch", R"(<launch>
  <hub port="seventy"/>
  <process name="p" program="/bin/true"/>
</launch>)");
  try {
    ReadLaunchFile(bad, {});
    FAIL() << "expected LaunchError";
  } catch (const LaunchError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":2: <hub> attribute port"),
              std::string::npos)
        << e.what();
  }
}

TEST(LaunchFile, ErrorsNameFileLineAndProblem) {
  const std::string unknown_var = WriteFile("b.launch", R"(<launch>
  <process name="sim" program="mrsim-sim" args="${nope}"/>
</launch>)");
  try {
    ReadLaunchFile(unknown_var, {});
    FAIL() << "expected LaunchError";
  } catch (const LaunchError& e) {
    EXPECT_NE(std::string(e.what()).find("b.launch:2:"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("${nope}"), std::string::npos);
  }
  const std::string duplicate = WriteFile("c.launch", R"(<launch>
  <process name="sim" program="a"/>
  <process name="sim" program="b"/>
</launch>)");
  EXPECT_THROW(ReadLaunchFile(duplicate, {}), LaunchError);
  const std::string bad_xml =
      WriteFile("d.launch", "<launch><process</launch>");
  EXPECT_THROW(ReadLaunchFile(bad_xml, {}), LaunchError);
  const std::string ok = WriteFile(
      "e.launch", R"(<launch><process name="a" program="true"/></launch>)");
  EXPECT_THROW(ReadLaunchFile(ok, {{"undeclared", "1"}}), LaunchError);
  // A misspelled attribute is an error, not silently ignored.
  for (const auto& [name, text] :
       std::vector<std::pair<std::string, std::string>>{
           {"f.launch",
            "<launch>\n<process name=\"a\" program=\"true\" "
            "requried=\"true\"/>\n</launch>"},
           {"g.launch",
            "<launch>\n<arg name=\"d\" defualt=\"1\"/>\n</launch>"}}) {
    try {
      ReadLaunchFile(WriteFile(name, text), {});
      ADD_FAILURE() << name << ": no error";
    } catch (const LaunchError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(name + ":2: unknown attribute"), std::string::npos)
          << what;
    }
  }
  // A delay or a finish time is the whole text, in seconds a launch can
  // mean.
  for (const std::string attribute : {"delay", "finish"}) {
    for (const char* seconds : {"1.0s", "1,0", "nan", "1e9", "-1", "abc", ""}) {
      const std::string path = WriteFile(
          "h.launch", "<launch>\n<process name=\"a\" program=\"true\" " +
                          attribute + "=\"" + seconds + "\"/>\n</launch>");
      try {
        ReadLaunchFile(path, {});
        ADD_FAILURE() << attribute << " '" << seconds << "': no error";
      } catch (const LaunchError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "h.launch:2: process 'a': attribute " + attribute +
                      ": expected seconds from 0 to 3600, got '" +
                      std::string(seconds) + "'"),
                  std::string::npos)
            << e.what();
      }
    }
  }
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadLaunchFile(path, {});
  } catch (const LaunchError& e) {
    return e.what();
  }
  return "";
}

TEST(LaunchFile, AReadyLineIsARegularExpressionCheckedWithItsLine) {
  const std::string ok = WriteFile("ready_ok.launch", R"(<launch>
  <process name="view" program="mrsim-view" ready="listening on \d+"/>
  <process name="sim" program="mrsim-sim"/>
</launch>)");
  const LaunchFile file = ReadLaunchFile(ok, {});
  EXPECT_EQ(file.processes[0].ready_line, "listening on \\d+");
  EXPECT_EQ(file.processes[1].ready_line, "");
  const std::string bad = WriteFile("ready_bad.launch", R"(<launch>

  <process name="view" program="mrsim-view" ready="listening (on"/>
</launch>)");
  try {
    ReadLaunchFile(bad, {});
    FAIL() << "expected LaunchError";
  } catch (const LaunchError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("ready_bad.launch:3:"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr(
                              "attribute ready: expected a regular expression, "
                              "got 'listening (on'"));
  }
}

TEST(LaunchFile, AnUnreadableFileIsSaidInWords) {
  const std::string missing = WriteFile("x.launch", "") + ".missing";
  EXPECT_EQ(ErrorOf(missing),
            missing + ": cannot read the launch file: no such file");
  const std::string folder = testing::TempDir("launch_file_folder");
  EXPECT_EQ(ErrorOf(folder), folder + ": is a folder, not a launch file");
  const std::string broken =
      WriteFile("broken.launch", "<launch>\n<process name=\"a\">\n</launch>\n");
  EXPECT_NE(ErrorOf(broken).find(
                "cannot read the launch file: an element is closed by "
                "another name, or not closed"),
            std::string::npos)
      << ErrorOf(broken);
}

TEST(LaunchFile, SplitArgsHonoursQuotes) {
  EXPECT_EQ(SplitArgs("a  'b c' \"d\"e"),
            (std::vector<std::string>{"a", "b c", "de"}));
  EXPECT_THROW(SplitArgs("'open"), std::invalid_argument);
}

TEST(LaunchFile, HostileFilesAreRefusedWithTheirLine) {
  // Each arg doubling the one before: 2^40 copies if nothing stopped it.
  std::string doubling = "<launch>\n<arg name=\"a0\" default=\"xxxxxxxx\"/>\n";
  for (int i = 1; i <= 40; ++i) {
    doubling += "<arg name=\"a" + std::to_string(i) + "\" default=\"${a" +
                std::to_string(i - 1) + "}${a" + std::to_string(i - 1) +
                "}\"/>\n";
  }
  const std::string error =
      ErrorOf(WriteFile("doubling.launch", doubling + "</launch>\n"));
  EXPECT_NE(error.find("doubling.launch:16: '${a13}${a13}' expands to more "
                       "than 64 KiB"),
            std::string::npos)
      << error;
  std::string deep = "<launch>\n";
  for (int i = 0; i < 10000; ++i) deep += "<process>";
  const std::string path = WriteFile("deep.launch", deep);
  EXPECT_EQ(ErrorOf(path), path +
                               ":2: elements nested more than 32 deep, "
                               "more than any mrsim file has");
}

}  // namespace
}  // namespace mrsim

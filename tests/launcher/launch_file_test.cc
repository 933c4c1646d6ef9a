#include "launcher/launch_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir("launch_file") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(LaunchFile, SubstitutesArgsAndOverrides) {
  const std::string path = WriteFile("a.launch", R"(<launch name="t">
  <arg name="out" default="outdir"/>
  <arg name="speed" default="2"/>
  <process name="sim" program="mrsim-sim" required="true"
           args="${launch_dir}/x.xml --speed ${speed} --out '${out}/a b'"/>
  <process name="viewer" program="mrsim-view" delay="0.5" enabled="false"/>
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
}

TEST(LaunchFile, SplitArgsHonoursQuotes) {
  EXPECT_EQ(SplitArgs("a  'b c' \"d\"e"),
            (std::vector<std::string>{"a", "b c", "de"}));
  EXPECT_THROW(SplitArgs("'open"), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim

// mrsim-sim given scenario files with values no physics can step: it must
// refuse them at once (exit 2, naming file, line and field), not run.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/child_process.h"
#include "tests/sim_process/sim_client.h"

namespace mrsim::testing {
namespace {

// The case study with line `line` (1-based) replaced by `text`.
std::string CaseStudyWithLine(const std::string& dir, int line,
                              const std::string& text) {
  std::ifstream in(SourcePath("scenarios/case_study.xml"));
  std::ostringstream out;
  std::string l;
  for (int n = 1; std::getline(in, l); ++n)
    out << (n == line ? text : l) << "\n";
  const std::string path = dir + "/case_study.xml";
  std::ofstream(path) << out.str();
  return path;
}

// Found by mutating the bundled scenarios: -1e308 in a frame's position
// passed validation and the simulator then stepped forever at sim time 0;
// +1e308 failed only at the first step.
TEST(HostileScenarioProcess, HugeFramePositionExitsTwoNamingFileLineAndField) {
  const std::string dir = TempDir("hostile_scenario_position");
  for (const char* value : {"-1e308", "1e308"}) {
    // Line 24 is the x of the first frame's <position> (line 23).
    const std::string path = CaseStudyWithLine(
        dir, 24, std::string("              <x>") + value + "</x>");
    ChildProcess sim({SimBinary(), path, "--clock", "fast", "--duration",
                      "0.02", "--lcm-url", TestLcmUrl(7347)},
                     dir + "/sim.log");
    EXPECT_EQ(sim.Wait(30.0), 2) << value << "\n" << sim.Output();
    const std::string out = sim.Output();
    EXPECT_NE(out.find("case_study.xml:23:"), std::string::npos) << out;
    EXPECT_NE(out.find("Frame[1]/position"), std::string::npos) << out;
    EXPECT_NE(out.find("expected x, y, z within"), std::string::npos) << out;
  }
}

}  // namespace
}  // namespace mrsim::testing

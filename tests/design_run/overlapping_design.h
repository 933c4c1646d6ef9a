// A design whose parts overlap at the start, for the tests of every
// program that refuses one: the case study with its ball ("ball") put
// where module 0 is.
#pragma once

#include <string>

#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim::testing {

// Writes it into `dir` and returns its path.
inline std::string WriteOverlappingDesign(const std::string& dir) {
  Scenario s = ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  s.scene_objects.at(0).position = s.robots.at(0).modules.at(0).position;
  const std::string path = dir + "/ball_in_the_robot.xml";
  WriteScenarioFile(s, path);
  return path;
}

}  // namespace mrsim::testing

// Gait files: one named parameter set in XML (docs/gait.md), so a gait
// found by the optimiser can be saved and run again by name or path.
//
//   <gait name="forward" kind="linear">
//     <A_pitch>1</A_pitch> <A_yaw>0</A_yaw> <phi_pitch>2.5</phi_pitch>
//     <phi_yaw>0</phi_yaw> <T>4</T> <offset_pitch>0</offset_pitch>
//     <offset_yaw>0</offset_yaw> <pitch_yaw_lag>0</pitch_yaw_lag>
//     <joint index="3" amplitude="0.2" phase="1.0" offset="0.1"/>
//     <cpg coupling="4" convergence="10" feedback="0"/>  (a CPG gait)
//   </gait>
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "gait_controller/gait.h"

namespace mrsim {

// A bad gait file or an unknown gait name. what() names the file, the line
// and the field, and what was expected.
class GaitFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads and validates one gait. The seven parameters are required;
// pitch_yaw_lag, kind (default linear), name (default: the file's stem),
// joint overrides and <cpg> (its attributes default to CpgParameters')
// are optional. Throws GaitFileError.
Gait ReadGaitFile(const std::string& path);
// As ReadGaitFile; `source` names the text in error messages.
Gait ReadGaitString(const std::string& xml, const std::string& source);

// Numbers are written in their shortest exact form, so reading gives back
// the same doubles.
std::string WriteGaitString(const Gait& gait);
// Writes through a temporary file and a rename, so an existing file is
// never left half-written. Throws GaitFileError naming the path.
void WriteGaitFile(const Gait& gait, const std::string& path);

// Where ResolveGait looks for NAME.xml: the directories of the environment
// variable MRSIM_GAIT_PATH (':'-separated), then ./gaits.
std::vector<std::string> GaitSearchPath();

// A preset name, a path to a gait file, or NAME with NAME.xml in the search
// path, in that order. Throws GaitFileError listing the presets when none
// matches, or the file's own error.
Gait ResolveGait(const std::string& spec);

}  // namespace mrsim

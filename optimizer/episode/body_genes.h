// Applies a genome's body genes to a copy of a scenario before an episode.
//
// joint_kp, joint_max_vel and module_mass change the robot in place (every
// hinge; each module's two frames get half the mass), and so does
// module_scale on its own (every length of every part scaled about the
// point at ground height, Scene::position.z, under module 0's hinge), so a
// hand-built robot (mesh frames, placed sensors) keeps its parts. module_count
// and sensor_after (and module_scale with either) rebuild the robot with
// MakeChain from options read off the robot (axis pattern, frame size, mass,
// Kp, max_vel, joint limit, material, sensor modules and their sensors, the
// ground point under module 0's hinge), so they suit MakeChain-style chains;
// see docs/optimizer.md.
#pragma once

#include "optimizer/search/genome.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Index of the robot the genome applies to (spec.robot, or 0). Throws
// GenomeError naming the robot when it is not in the scenario.
int GenomeRobotIndex(const Scenario& scenario, const GenomeSpec& spec);

// The MakeChain options that rebuild `robot` as it is (the inverse of
// MakeChain for the chains it makes).
ChainOptions ChainOptionsOf(const Robot& robot);

// Whether the genome builds the robot's shape (module_count, module_scale,
// sensor_after): such bodies are checked for parts overlapping at the
// start, as mrsim-sim checks a file (the genes' limits may grow a body
// into the ball in front of it or the terrain around it).
bool GenomeBuildsTheBody(const GenomeSpec& spec);

// The scenario with the body genes applied. Throws GenomeError when the
// robot cannot be rebuilt (no modules).
Scenario ApplyBodyGenes(const Scenario& scenario, const GenomeSpec& spec,
                        const Genome& genome);

}  // namespace mrsim

// Structural edits of a chain robot (insert, remove, reorder parts). The
// robot is laid out again with MakeChain's geometry
// (sim_core/scenario/chain_builder.h) so a chain built part by part equals what
// `mrsim-scenario new` makes; the fields a user edited on existing parts
// (masses, materials, gains, limits, sensors) are carried over.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim::studio {

// One part of a chain from front to back: a module or a sensor module.
// `source` is its index in the robot being edited, or -1 for a new part.
struct ChainSlot {
  bool sensor = false;
  int source = -1;
  Axis axis = Axis::kPitch;  // modules only
};

// The parts of `robot` from front to back: modules in list order, each
// sensor module after the module named by its left_mod_nr (-1: in front).
std::vector<ChainSlot> ChainOrder(const Robot& robot);

// The chain options a new part of `robot` takes (frame size, mass,
// material, gains and origin of its module 0); ChainOptions' defaults for an
// empty robot.
ChainOptions OptionsOf(const Robot& robot);

// Lays out `slots` as a chain with `options` (name, sizes, origin) and
// carries the edited fields of the parts `slots` take from `old`. Throws
// std::invalid_argument when the chain cannot be built: no module, or two
// sensor modules next to each other.
// A new module takes the mesh frames (shape and scale) of the first
// module of its kind in `old` that has them. Mesh frames are measured with
// `base_dir` (Restack). The chain's locks keep their breaking force when
// they join the same two parts again; loop locks whose two parts remain
// are carried, naming the parts by their new guids.
Robot Relayout(const Robot& old, const std::vector<ChainSlot>& slots,
               const ChainOptions& options, const std::string& base_dir = "");

// A lock of `robot` that joins the back of one part to the front of the
// next in the chain (ChainOrder; a module's back and front frames, a
// sensor module itself): the chain's own, which Relayout makes again. Any other
// lock closes a loop (or braces two parts apart) and Relayout carries it.
bool IsChainLock(const Robot& robot, const Joint& lock);

// Puts the force plate and distance sensors of `sm` on the centres of
// their faces (sensorPosition) of the module as it is now, as the physics
// mounts them; parts already there keep their exact coordinates.
void PlaceMounted(SensorModule* sm);

// Slides the parts of `robot` along the chain (x) so each touches the one
// in front with its own length (its frames' scale, a sensor module's size),
// module 0's hinge staying put; what is mounted on a sensor module moves
// with it. Parts that already touch keep their exact coordinates. A mesh
// frame's length is its mesh's bounds along x (read with `base_dir`, the
// design's folder); a robot whose mesh cannot be read is left as it is.
void Restack(Robot* robot, const std::string& base_dir = "");

}  // namespace mrsim::studio

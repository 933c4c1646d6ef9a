// What drives the robot in an optimiser's episode (`mrsim-opt --controller
// KIND`), part of the Problem: it travels in the problem payload to farm
// workers and so is part of the run's fingerprint (a worker runs exactly
// the master's controller; a checkpoint of another controller is refused).
//
// Adding a kind (e.g. a neural network): a value in ControllerSpec::Kind
// and its word in Kinds(); its flag in ParseControllerFlag; what its
// payload section carries in EncodeControllerSpec/DecodeControllerSpec;
// its genes in ControllerGenome (controller_genes.h); its episode
// controller in MakeEpisodeController (episode_controller.cc); its best
// file and replay process in WriteBestControllerFile and
// ReplayControllerProcess (process/opt_command.cc). The compiler points at
// every switch over Kind that lacks the new value.
#pragma once

#include <string>
#include <vector>

#include "common/enum_table.h"

namespace mrsim {

struct ControllerSpec {
  // kGait: the built-in gait (its genes in the genome; `cpg` on the
  // command line is the gait with the CPG genes). kLua: a Lua script whose
  // declared parameters are the genes (lua_script.h, LuaParameter).
  // kMlp: a neural network whose weights are the genes (mlp_genes.h).
  enum class Kind { kGait, kLua, kMlp };
  // The words of --controller and of the payload for each kind.
  static const EnumTable<Kind>& Kinds();

  Kind kind = Kind::kGait;
  // kLua: the script's text and the name it goes by (its file name, in
  // error messages and best_controller.lua's header).
  std::string source;
  std::string name;
  // kMlp: the hidden layer sizes (mlp:8 -> {8}) and the robot's hinge
  // count, which fixes the network's size (ResolveMlpJoints; 0 until
  // resolved).
  std::vector<int> hidden;
  int joints = 0;
  // kMlp: the optional inputs (mlp:H+imu+sensors, docs/nn.md): the robot's
  // orientation and CoM velocity, and its sensor values (sensors: -1 until
  // ResolveMlpJoints counts the robot's; then how many, 0: none).
  bool imu = false;
  int sensors = 0;

  bool is_gait() const { return kind == Kind::kGait; }
};

// What --controller says. "gait" and "cpg" (the gait; cpg_genes says the
// default genome is the CPG one); "lua:FILE" reads FILE (at most
// kMaxLuaScriptBytes); "mlp:H" or "mlp:H1,H2" a network with those hidden
// layers (its joints still to resolve), with "+imu" and/or "+sensors"
// after them for those inputs. Throws std::invalid_argument naming the
// flag and what it accepts, or the file that does not read.
ControllerSpec ParseControllerFlag(const std::string& text,
                                   bool* cpg_genes = nullptr);

// The payload's "controller" section (none for the gait, so a gait
// problem's payload and fingerprint are what they were before kinds).
std::string EncodeControllerSpec(const ControllerSpec& spec);
// Throws std::invalid_argument naming `source` on a malformed section.
ControllerSpec DecodeControllerSpec(const std::string& text,
                                    const std::string& source);

}  // namespace mrsim

// The flags mrsim-gait and mrsim-lua share (CLI11): which robot, the LCM
// connection, the channel prefix, where the joint axes come from, the
// rate, the sender name and --exit-with-sim, and how they resolve, so both
// programs declare and check them the same way.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "lcmtypes/runtime/auth_flags.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

struct ControllerFlags {
  // What differs between the programs' help texts.
  struct Help {
    std::string scenario_gives;  // "(gives X; without it or --axes, ...)"
    std::string rate;            // --rate's help
    std::string exit_with_sim;   // --exit-with-sim's help
  };
  // The node options' fields the flags write: their defaults stay the
  // node options' own.
  struct NodeFields {
    std::string* prefix = nullptr;
    double* rate = nullptr;
    bool* exit_with_sim = nullptr;
  };

  // "gait" or "lua": the default sender is "<kind>-<robot>".
  explicit ControllerFlags(std::string kind) : kind(std::move(kind)) {}

  std::string kind;
  std::string robot;
  std::string lcm_url;
  AuthFlags auth;
  std::string scenario_path;
  std::string axes_text;
  std::string name;

  // Filled by Finish().
  std::string sender;
  std::function<std::vector<Axis>(int)> axes_for;
  std::string warning;  // for stderr, or empty

  // Declares --robot, --lcm-url, the auth flags, --prefix, --scenario,
  // --axes, --rate, --name and --exit-with-sim on `app`.
  void AddFlags(CLI::App& app, NodeFields fields, const Help& help);
  // Resolves the sender and the joint axes (pitch-yaw when neither
  // --scenario nor --axes is given: then `warning` is no_axes_warning) and
  // checks --rate. Throws UsageError naming the flag.
  void Finish(const std::string& no_axes_warning);

 private:
  NodeFields fields_;
};

}  // namespace mrsim

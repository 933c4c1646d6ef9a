// A user's controller written in Lua, run in a sandbox: the script defines
// `function step(t, state) ... return {angle, ...} end` and is asked for
// one joint target per hinge joint (radians) at each control step
// (docs/gait.md, "Lua controllers"). The sandbox has no io, os, package,
// debug, coroutine, load or string.dump; every call is bounded by an
// instruction count, and the whole interpreter by a memory limit, so an
// endless loop or a runaway table ends in a LuaScriptError instead of a
// hung or crashed controller. print() is kept: its lines are collected
// (TakePrinted) for the caller to show. No LCM here: the state is a plain
// struct (mrsim-lua fills it from robot_state_t, tests by hand).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/input_limits.h"

namespace mrsim {

struct LuaLimits {
  // Lua VM instructions per call (the script's top level counts as one
  // call): about 0.1-1 s of work, far above any sensible step.
  int64_t instructions = 50'000'000;
  size_t memory_bytes = size_t{64} << 20;
  size_t max_source_bytes = kMaxLuaScriptBytes;
  size_t max_printed_lines = 1000;
};

// Thrown for a script that does not compile, fails at run time, runs out of
// instructions or memory, or returns the wrong thing. line() is the script
// line the message points at (0 when it names none); what() is the whole
// message, "NAME:LINE: ...".
class LuaScriptError : public std::runtime_error {
 public:
  LuaScriptError(const std::string& message, int line)
      : std::runtime_error(message), line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

// What step() is given as `state` besides `t` (the sim time): the robot's
// joints in chain order (rad, rad/s, N m), its centre of mass (m, m/s), its
// orientation (quaternion w, x, y, z) and heading (rad; docs/sim.md), and
// each sensor module's force (N, when it has one) and distances (m), and
// every reading of every sensor kind the module carries (force, distance,
// IMU, and any kind added later), and each joint's axis ("pitch" or "yaw";
// empty when unknown).
struct LuaRobotState {
  std::vector<std::string> axes;
  std::vector<double> angles;
  std::vector<double> speeds;
  std::vector<double> torques;
  double com[3] = {0, 0, 0};
  double com_velocity[3] = {0, 0, 0};
  double orientation[4] = {1, 0, 0, 0};  // w, x, y, z
  double heading = 0;
  // One sensor's values, in its kind's channel order (sim_core's
  // SensorKinds(): the IMU's accel.x/y/z m/s^2 then gyro.x/y/z rad/s).
  struct Reading {
    std::string kind;  // "force", "distance", "imu", ...
    int face = -1;     // 0..5, or -1 when it sits on no face
    std::vector<double> values;
  };
  struct Sensor {
    double force = 0;
    bool has_force = false;
    std::vector<double> distances;
    std::vector<Reading> readings;  // every sensor of the module, any kind
  };
  std::vector<Sensor> sensors;
  // The robot's cameras in camera_image_t's numbering (state.cameras[k + 1]
  // is camera k): the picture mrsim-lua picked for this state (docs/lua.md,
  // "Cameras"), seq -1 and empty grey when none has come yet.
  struct Camera {
    int width = 0;  // the picture's size (px)
    int height = 0;
    int64_t seq = -1;  // the state it shows
    double sim_time = 0;
    int grey_width = 0;  // the thumbnail's size
    int grey_height = 0;
    std::vector<double> grey;  // row-major, top row first, 0..1
  };
  std::vector<Camera> cameras;
};

// A tunable constant the script declares (mrsim-opt --controller lua:FILE
// makes each a gene; docs/optimizer.md, "Lua controllers as genomes"): the
// global `params` is an array, in gene order, of tables
// {name = "amplitude", min = 0, max = 1.5, start = 0.6}. After the top
// level runs, the global table P holds each parameter's value by name:
// its start, or what SetParameters gives (the optimiser's genes).
struct LuaParameter {
  std::string name;
  double min = 0;
  double max = 0;
  double start = 0;
};

// A steering request as on_gait_command(cmd) sees it: cmd.motion and
// cmd.strength, cmd.gait, cmd.parameters (7 numbers) and cmd.forward /
// cmd.turn, each present only when the gait command carries it.
struct LuaGaitCommand {
  std::string sender;
  std::string motion;  // "" when absent
  double strength = 0;
  std::string gait;                // "" when absent
  std::vector<double> parameters;  // empty or 7 numbers
  bool has_direction = false;
  double forward = 0;
  double turn = 0;
};

class LuaScript {
 public:
  // Compiles `source` and runs its top level (defining step). `name` is
  // the chunk name error messages start with (the file name). Throws
  // LuaScriptError with the line for a syntax error, an error at the top
  // level, no `step` function, or a `params` declaration that is not an
  // array of {name, min, max, start} (the message names the entry and
  // field).
  LuaScript(const std::string& source, const std::string& name,
            LuaLimits limits = {});
  ~LuaScript();
  LuaScript(const LuaScript&) = delete;
  LuaScript& operator=(const LuaScript&) = delete;

  // The error LuaScript(source, name) would throw, or nothing: what the
  // studio shows before Run.
  static std::optional<LuaScriptError> Check(const std::string& source,
                                             const std::string& name);

  // Calls step(t, state) and returns its targets: exactly one finite
  // number per joint of `state`. Throws LuaScriptError (line included when
  // the script's) for an error in step, the instruction or memory limit,
  // or a result of the wrong shape. The script's globals persist between
  // calls.
  std::vector<double> Step(double t, const LuaRobotState& state);

  // Whether the script defines on_gait_command(cmd): it then takes
  // steering, and mrsim-lua says so by sending a gait status (docs/gait.md,
  // "Who takes steering").
  bool takes_gait_commands() const;
  // Calls on_gait_command(cmd) with the command's parts as a table (see
  // LuaGaitCommand). Returns "" when the script took it, else why it
  // refused (it returned false, and perhaps a reason). Throws
  // LuaScriptError as Step does; std::logic_error without the function.
  std::string OnGaitCommand(const LuaGaitCommand& command);

  // The script's declared parameters (empty without `params`).
  const std::vector<LuaParameter>& parameters() const { return parameters_; }
  // Sets P[name] = values[i] for each declared parameter, in declaration
  // order. Throws std::invalid_argument for the wrong count or a value
  // that is not finite.
  void SetParameters(const std::vector<double>& values);

  // Lines the script printed since the last call (at most
  // max_printed_lines are kept).
  std::vector<std::string> TakePrinted();

  const std::string& name() const { return name_; }

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
  std::string name_;
  std::vector<LuaParameter> parameters_;
};

}  // namespace mrsim

// The sizes mrsim accepts in the files it reads (scenarios, gaits, genomes,
// launch files, checkpoints, height images), checked before a byte is
// parsed or a buffer sized from the file, so a hostile or broken file is
// refused with its name and line instead of exhausting memory or the stack.
// The numbers are in docs/scenario.md, "Limits".
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mrsim {

// The largest file any reader takes: a scenario with a height image or a
// mesh embedded as base64, or a checkpoint holding one.
inline constexpr size_t kMaxInputFileBytes = size_t{64} << 20;  // 64 MiB
// Elements nested deeper than this: mrsim's deepest file (a scenario's
// Scenario/robot/sensorModules/SensorModule/distanceSensors/
// DistanceSensor/ray_Direction/x) is 8 deep. tinyxml2 parses recursively.
inline constexpr int kMaxXmlDepth = 32;
// A longer attribute value: every attribute mrsim reads is a name, a
// number or a command line.
inline constexpr size_t kMaxXmlAttributeBytes = size_t{64} << 10;  // 64 KiB
// The longest Lua controller script, wherever it comes from: a scenario's
// <run><luaScript>, a --script file of mrsim-lua, the studio's editor. One
// value, because a script written in the studio is saved in the scenario
// and must load back in mrsim-lua. 64 KiB (the studio once allowed 1 MiB,
// which saved designs mrsim refused to read): some 1500 lines, far more
// than any controller, and as much as any one XML attribute may hold.
inline constexpr size_t kMaxLuaScriptBytes = size_t{64} << 10;  // 64 KiB

// A file beyond one of the limits. what() is "FILE:LINE: what was found
// (the limit)", or "FILE: ..." when no line applies.
class InputLimitError : public std::runtime_error {
 public:
  InputLimitError(const std::string& file, int line, const std::string& what);
  int line() const { return line_; }

 private:
  int line_;
};

// The whole file, or nullopt when it cannot be opened (errno says why).
// Reads at most max_bytes + 1 bytes, so a FIFO, /dev/zero or a file that
// grows is refused too. Throws InputLimitError when it is longer.
std::optional<std::string> ReadFileAtMost(
    const std::string& path, size_t max_bytes = kMaxInputFileBytes);

// Scans XML text without parsing it: its size, element nesting depth and
// attribute lengths against the limits above. `file` names it in errors.
// Throws InputLimitError at the first one exceeded.
void CheckXmlLimits(std::string_view xml, const std::string& file);

}  // namespace mrsim

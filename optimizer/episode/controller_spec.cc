#include "optimizer/episode/controller_spec.h"

#include <fmt/format.h>

#include <optional>
#include <stdexcept>

#include "common/input_limits.h"
#include "nn_controller/mlp_shape.h"

namespace mrsim {

const EnumTable<ControllerSpec::Kind>& ControllerSpec::Kinds() {
  static const EnumTable<Kind> kKinds("controller kind",
                                      {{ControllerSpec::Kind::kGait, "gait"},
                                       {ControllerSpec::Kind::kLua, "lua"},
                                       {ControllerSpec::Kind::kMlp, "mlp"}});
  return kKinds;
}

namespace {

constexpr const char* kFlagHelp =
    "expected gait, cpg, lua:FILE or mlp:H (mlp:H1,H2; +imu, +sensors "
    "for those inputs)";

// The network's name in resume messages and best_network.xml: "8,8+imu".
std::string MlpName(const ControllerSpec& spec) {
  return HiddenLayersText(spec.hidden) + (spec.imu ? "+imu" : "") +
         (spec.sensors != 0 ? "+sensors" : "");
}

// The name a script goes by: its file name, without the folders.
std::string ScriptName(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

ControllerSpec ParseControllerFlag(const std::string& text, bool* cpg_genes) {
  if (cpg_genes != nullptr) *cpg_genes = false;
  ControllerSpec spec;
  if (text == "gait") return spec;
  if (text == "cpg") {
    if (cpg_genes != nullptr) *cpg_genes = true;
    return spec;
  }
  const std::string lua = "lua:";
  if (text.rfind(lua, 0) == 0 && text.size() > lua.size()) {
    const std::string path = text.substr(lua.size());
    std::optional<std::string> source;
    try {
      source = ReadFileAtMost(path, kMaxLuaScriptBytes);
    } catch (const InputLimitError& e) {
      throw std::invalid_argument("--controller " + text + ": " + e.what());
    }
    if (!source) {
      throw std::invalid_argument("--controller " + text + ": cannot read " +
                                  path);
    }
    spec.kind = ControllerSpec::Kind::kLua;
    spec.source = std::move(*source);
    spec.name = ScriptName(path);
    return spec;
  }
  const std::string mlp = "mlp:";
  if (text.rfind(mlp, 0) == 0) {
    spec.kind = ControllerSpec::Kind::kMlp;
    std::string rest = text.substr(mlp.size());
    const size_t plus = rest.find('+');
    const std::string layers = rest.substr(0, plus);
    rest = plus == std::string::npos ? "" : rest.substr(plus);
    spec.hidden = ParseHiddenLayers(layers, "--controller " + text);
    while (!rest.empty()) {  // "+imu", "+sensors", each at most once
      const size_t next = rest.find('+', 1);
      const std::string input = rest.substr(1, next - 1);
      rest = next == std::string::npos ? "" : rest.substr(next);
      if (input == "imu" && !spec.imu) {
        spec.imu = true;
      } else if (input == "sensors" && spec.sensors == 0) {
        spec.sensors = -1;  // the robot's count, once resolved
      } else {
        throw std::invalid_argument(fmt::format(
            "--controller '{}': input '+{}' (expected +imu and/or +sensors, "
            "each once)",
            text, input));
      }
    }
    spec.name = MlpName(spec);  // "controller=mlp:8,8+imu"
    return spec;
  }
  throw std::invalid_argument(
      fmt::format("--controller '{}': {}", text, kFlagHelp));
}

std::string EncodeControllerSpec(const ControllerSpec& spec) {
  if (spec.is_gait()) return "";
  // The name is a file name (no newline); the source, the rest, verbatim.
  // A network's shape: its hidden layers and the joints it was made for.
  const std::string shape =
      spec.kind == ControllerSpec::Kind::kMlp
          ? fmt::format(
                "hidden={}\njoints={}\n{}{}", HiddenLayersText(spec.hidden),
                spec.joints, spec.imu ? "imu=1\n" : "",
                spec.sensors != 0 ? fmt::format("sensors={}\n", spec.sensors)
                                  : "")
          : "";
  return fmt::format("kind={}\nname={}\n{}\n{}",
                     ControllerSpec::Kinds().Name(spec.kind), spec.name, shape,
                     spec.source);
}

ControllerSpec DecodeControllerSpec(const std::string& text,
                                    const std::string& source) {
  const std::string where = source + ": controller section";
  ControllerSpec spec;
  size_t pos = 0;
  bool have_kind = false;
  for (;;) {
    const size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) {
      throw std::invalid_argument(where + ": no blank line before the body");
    }
    const std::string line = text.substr(pos, eol - pos);
    pos = eol + 1;
    if (line.empty()) break;
    const size_t eq = line.find('=');
    const std::string key = line.substr(0, eq);
    const std::string value =
        eq == std::string::npos ? "" : line.substr(eq + 1);
    if (key == "kind") {
      spec.kind = ControllerSpec::Kinds().Parse(value, where + " kind");
      have_kind = true;
    } else if (key == "name") {
      spec.name = value;
    } else if (key == "hidden") {
      spec.hidden = ParseHiddenLayers(value, where + " hidden");
    } else if (key == "joints") {
      const bool digits =
          !value.empty() && value.size() <= 5 &&
          value.find_first_not_of("0123456789") == std::string::npos;
      spec.joints = digits ? std::stoi(value) : 0;
      if (spec.joints < 1 || spec.joints > MlpShape::kMaxJoints) {
        throw std::invalid_argument(
            fmt::format("{} joints: expected 1 to {}, got '{}'", where,
                        MlpShape::kMaxJoints, value));
      }
    } else if (key == "imu" && value == "1") {
      spec.imu = true;
    } else if (key == "sensors") {
      const bool digits =
          !value.empty() && value.size() <= 5 &&
          value.find_first_not_of("0123456789") == std::string::npos;
      spec.sensors = digits ? std::stoi(value) : 0;
      if (spec.sensors < 1 || spec.sensors > MlpShape::kMaxSensors) {
        throw std::invalid_argument(
            fmt::format("{} sensors: expected 1 to {}, got '{}'", where,
                        MlpShape::kMaxSensors, value));
      }
    } else {
      throw std::invalid_argument(where + ": unknown field '" + key + "'");
    }
  }
  if (!have_kind) throw std::invalid_argument(where + ": no kind");
  spec.source = text.substr(pos);
  if (spec.kind == ControllerSpec::Kind::kMlp &&
      (spec.hidden.empty() || spec.joints == 0 || !spec.source.empty())) {
    throw std::invalid_argument(
        where + ": a network needs hidden= and joints= and no body");
  }
  if (spec.kind == ControllerSpec::Kind::kLua) {
    if (spec.source.size() > kMaxLuaScriptBytes) {
      throw std::invalid_argument(
          fmt::format("{}: the script has {} bytes; at most {}", where,
                      spec.source.size(), kMaxLuaScriptBytes));
    }
    if (spec.name.empty()) spec.name = "script.lua";
  }
  return spec;
}

}  // namespace mrsim
